// An archive as bytes and back, each key and its values in order: what one process sends the others (process 0
// reads a checkpoint and the others receive it).
#pragma once
#include "engine/archive.hpp"
#include "engine/bytes.hpp"

namespace mc {

Bytes archive_bytes(const Archive& a);
Archive archive_of(const Bytes& in);

}  // namespace mc
