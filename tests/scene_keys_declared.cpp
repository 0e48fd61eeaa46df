// Every key a scene may hold is declared once, in a key table (engine/keys.hpp), and read from there:
//  1. reading every scene of the tree (the shipped scenes, the specimens' and the tests' own) asks for no key that
//     its table does not declare (a reader asking for one throws std::logic_error), and asks, between them all, for
//     every key the tables declare: a declared key that no reader reads is a documented key the program ignores;
//  2. the key reference (docs/keys.md) is what the tables say, written by `mesocrack keys --markdown`;
//  3. every key says what it is, and a key's name is unique in its table but for one declaration per case (`when`).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "engine/errors.hpp"
#include "scene/key_reader.hpp"
#include "scene/key_reference.hpp"
#include "scene/scene.hpp"
#include "scene/scene_keys.hpp"
#include "scene/toml_reader.hpp"

using namespace mc;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = MESOCRACK_SOURCE_DIR;

// The scene files of the tree: every .toml under scenes/ and tests/.
std::vector<fs::path> scene_files() {
  std::vector<fs::path> out;
  for (const char* dir : {"scenes", "tests"})
    for (const auto& e : fs::recursive_directory_iterator(kSource / dir))
      if (e.path().extension() == ".toml") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::string qualified(const KeyTable& t, const Key& k) {
  return std::string(t.name) + "." + std::string(k.name) + (k.when.empty() ? "" : " (" + std::string(k.when) + ")");
}

}  // namespace

TEST_CASE("every_key_read_is_declared_and_every_declared_key_is_read_by_the_scenes_of_the_tree") {
  const std::vector<fs::path> files = scene_files();
  REQUIRE(files.size() > 40);
  int read = 0;
  for (const fs::path& f : files) {
    // A scene of the tree may be a deliberately bad one (the tests' refused inputs): an InputError is fine, a key
    // its table does not declare (std::logic_error) is not.
    try {
      read_scene(TomlDoc::load(f.string()), f.string());
      ++read;
    } catch (const InputError&) {
    } catch (const IoError&) {
    }
  }
  MESSAGE(read, " of ", files.size(), " scene files read whole");
  CHECK(read > 40);
  const std::set<const Key*> asked = keys_asked();
  std::string never;
  for (const KeyTable* t : all_key_tables())
    for (const Key& k : t->keys)
      if (!asked.count(&k)) never += "\n  " + qualified(*t, k);
  CHECK_MESSAGE(never.empty(), "declared, and read by no scene of the tree:", never);
}

TEST_CASE("key_reference_page_is_what_the_key_tables_declare") {
  std::ifstream in(kSource / "docs" / "keys.md");
  REQUIRE_MESSAGE(in.good(), "docs/keys.md is missing: write it with build/mesocrack keys --markdown > docs/keys.md");
  std::stringstream page;
  page << in.rdbuf();
  CHECK_MESSAGE(page.str() == key_reference_markdown(),
                "docs/keys.md differs from the key tables: write it again with build/mesocrack keys --markdown > "
                "docs/keys.md");
}

TEST_CASE("every_declared_key_says_what_it_is_and_is_declared_once_per_case") {
  std::set<std::string> tables;
  for (const KeyTable* t : all_key_tables()) {
    CHECK_MESSAGE(tables.insert(std::string(t->name)).second, "two tables named ", std::string(t->name));
    CHECK_MESSAGE(!t->about.empty(), std::string(t->name), " says nothing of itself");
    std::set<std::string> keys;
    for (const Key& k : t->keys) {
      CHECK_MESSAGE(!k.doc.empty(), qualified(*t, k), " has no description");
      CHECK_MESSAGE(keys.insert(std::string(k.name) + "|" + std::string(k.when)).second, qualified(*t, k),
                    " is declared twice");
      if (k.type == KeyType::Word) CHECK_MESSAGE(!k.words.empty(), qualified(*t, k), " allows no word");
    }
  }
}
