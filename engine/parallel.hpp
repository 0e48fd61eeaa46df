// How the engine splits work between threads so that results do not depend on the thread count.
#pragma once
#include <cstddef>

namespace mc {

// Sums of floating-point numbers must not depend on the thread count: contacts are summed in fixed blocks,
// and the block sums are added in order.
inline constexpr int kBlock = 1024;
// Below this many items a loop runs on one thread: forking a team costs more than the work, and on a busy
// machine a spinning team waiting for a descheduled thread can cost milliseconds per step.
inline constexpr int kParallelMin = 4096;
inline int block_count(std::size_t n) { return static_cast<int>((n + kBlock - 1) / kBlock); }
// The force pass's blocks: the pairs whose A is of one group of kGroup consecutive particles of the whole world's
// numbering (Slots). Larger groups keep more pairs within a group (along a Morton curve in 3D: 72 % with 256, 78 %
// with 512, 83 % with 1024) but leave fewer blocks to share between threads.
inline constexpr int kGroup = 512;

}  // namespace mc
