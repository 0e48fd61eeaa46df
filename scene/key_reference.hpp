// The key reference, written from the key tables (engine/keys.hpp) and nothing else: `mesocrack keys [TABLE]` on a
// terminal, and docs/keys.md (`mesocrack keys --markdown`), which a test keeps equal to what the tables say.
#pragma once
#include <string>

namespace mc {

// Every table's name and heading, one per line.
std::string key_table_list();
// One table (by its name, e.g. "walls", "cpm", "run.stop") as text; InputError naming the tables when it is none.
std::string key_table_text(const std::string& name);
// Every table as Markdown: the docs page.
std::string key_reference_markdown();

}  // namespace mc
