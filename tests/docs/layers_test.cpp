// The layer table in docs/architecture.md ("The layer table") is the rule: every source folder is
// listed with the folders it may include and link. This test reads the table and checks every
// quoted include of every source file, and every link dependency the build configured
// (layer_links.txt, written by cmake/layers.cmake), against it. A file in a folder the table does
// not list fails too, so a new folder must be placed before it builds.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/tools.h"

namespace hitl {
namespace {

namespace fs = std::filesystem;

/// folder -> the folders it may include and link (patterns: "base/*" is every folder under base/).
using LayerTable = std::map<std::string, std::vector<std::string>>;

/// The ```layers block of docs/architecture.md: "folder: allowed allowed ..." lines, # comments.
LayerTable parse_layer_table(const std::string& markdown) {
  LayerTable table;
  const auto start = markdown.find("```layers\n");
  if (start == std::string::npos) return table;
  const auto end = markdown.find("```", start + 10);
  std::istringstream lines(markdown.substr(start + 10, end - start - 10));
  for (std::string line; std::getline(lines, line);) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::istringstream words(line.substr(colon + 1));
    std::vector<std::string> allowed;
    for (std::string word; words >> word;) allowed.push_back(word);
    std::string folder = line.substr(0, colon);
    folder.erase(std::remove(folder.begin(), folder.end(), ' '), folder.end());
    table[folder] = allowed;
  }
  return table;
}

/// The listed folder a path lies in (the longest listed prefix), or "" when none.
std::string folder_of(const LayerTable& table, const std::string& path) {
  std::string best;
  for (const auto& [folder, allowed] : table)
    if (path.rfind(folder + "/", 0) == 0 && folder.size() > best.size()) best = folder;
  return best;
}

bool allows(const LayerTable& table, const std::string& from, const std::string& to) {
  if (from == to) return true;
  for (const auto& pattern : table.at(from)) {
    if (pattern == to) return true;
    if (pattern.size() > 2 && pattern.ends_with("/*") && to.rfind(pattern.substr(0, pattern.size() - 1), 0) == 0)
      return true;
  }
  return false;
}

/// Top-level folders whose root-relative include strings the table governs.
const std::set<std::string> kLayeredRoots = {"base", "target", "engine", "emulator", "tui", "cli", "tests", "bench"};

/// "file: includes X (folder F), which folder G may not include" for each violation in `files`
/// (path relative to the root -> its text).
std::vector<std::string> include_violations(const LayerTable& table, const std::map<std::string, std::string>& files) {
  std::vector<std::string> out;
  static const std::regex kInclude(R"re(#\s*include\s*"([^"]+)")re");
  for (const auto& [path, text] : files) {
    const std::string from = folder_of(table, path);
    if (from.empty()) {
      out.push_back(path + ": its folder is not in the layer table (docs/architecture.md)");
      continue;
    }
    for (std::sregex_iterator it(text.begin(), text.end(), kInclude), end; it != end; ++it) {
      const std::string included = (*it)[1];
      if (included.rfind("../", 0) == 0 || included.find("/../") != std::string::npos) {
        // "../hil/x.h" from engine/net names no folder the table can check: it climbs out of its own.
        out.push_back(path + ": includes " + included + ", a relative path that climbs out of its folder; "
                      "write it from the root (\"engine/hil/x.h\") so the layer table governs it");
        continue;
      }
      const auto slash = included.find('/');
      if (slash == std::string::npos || !kLayeredRoots.count(included.substr(0, slash))) continue;  // local or external
      const std::string to = folder_of(table, included);
      if (to.empty()) {
        out.push_back(path + ": includes " + included + ", which is in no folder of the layer table");
      } else if (!allows(table, from, to)) {
        out.push_back(path + ": includes " + included + ": " + from + " may not include " + to);
      }
    }
  }
  return out;
}

std::map<std::string, std::string> source_files(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const char* top : {"base", "target", "engine", "emulator", "tui", "cli"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      const auto ext = entry.path().extension();
      if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp" || ext == ".hpp"))
        files[fs::relative(entry.path(), root).generic_string()] = test::read_text(entry.path().string());
    }
  }
  return files;
}

LayerTable the_table() { return parse_layer_table(test::read_text(test::source_path("docs/architecture.md"))); }

TEST(Layers, TheTableIsThere) {
  const auto table = the_table();
  ASSERT_FALSE(table.empty()) << "docs/architecture.md has no ```layers block";
  for (const char* folder : {"base/common", "base/mavlink", "base/contract", "target/core", "engine/hil", "emulator", "tui", "cli"})
    EXPECT_TRUE(table.count(folder)) << folder;
}

TEST(Layers, NoIncludeRunsUpOrAcross) {
  const auto table = the_table();
  ASSERT_FALSE(table.empty());
  const auto files = source_files(HITL_SOURCE_DIR);
  ASSERT_GT(files.size(), 300U);
  for (const auto& violation : include_violations(table, files)) ADD_FAILURE() << violation;
}

TEST(Layers, TheCheckCatchesAnUpwardInclude) {
  const LayerTable table = {{"base/common", {}}, {"engine/net", {"base/*"}}, {"engine/hil", {"base/*", "engine/net"}}};
  const std::map<std::string, std::string> files = {
      {"engine/hil/a.cpp", "#include \"engine/net/x.h\"\n#include \"base/common/clock.h\"\n#include <vector>\n"},
      {"engine/net/x.h", "#include \"engine/hil/a.h\"\n"},            // up
      {"base/common/clock.h", "#include \"engine/net/x.h\"\n"},      // up from the base
      {"engine/new/y.cpp", "#include \"base/common/clock.h\"\n"},   // a folder not in the table
      {"engine/net/z.cpp", "#include \"../hil/a.h\"\n#include \"z_impl.h\"\n"}};  // climbs out, past the table
  const auto found = include_violations(table, files);
  ASSERT_EQ(found.size(), 4U);
  EXPECT_NE(found[0].find("base/common may not include engine/net"), std::string::npos) << found[0];
  EXPECT_NE(found[1].find("engine/net may not include engine/hil"), std::string::npos) << found[1];
  EXPECT_NE(found[2].find("engine/net/z.cpp: includes ../hil/a.h, a relative path that climbs"), std::string::npos)
      << found[2];
  EXPECT_NE(found[3].find("not in the layer table"), std::string::npos) << found[3];
}

/// layer_links.txt: "library|folder ...|linked ..." per hitl library.
struct LibraryLinks {
  std::vector<std::string> folders;
  std::vector<std::string> links;
};

std::map<std::string, LibraryLinks> read_links() {
  std::map<std::string, LibraryLinks> libraries;
  std::istringstream lines(test::read_text(HITL_LAYER_LINKS));
  for (std::string line; std::getline(lines, line);) {
    const auto a = line.find('|'), b = line.find('|', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    LibraryLinks l;
    std::istringstream folders(line.substr(a + 1, b - a - 1)), links(line.substr(b + 1));
    for (std::string w; folders >> w;) l.folders.push_back(w);
    for (std::string w; links >> w;) l.links.push_back(w);
    libraries[line.substr(0, a)] = l;
  }
  return libraries;
}

TEST(Layers, NoLinkRunsUpOrAcross) {
  const auto table = the_table();
  const auto libraries = read_links();
  ASSERT_GT(libraries.size(), 15U) << HITL_LAYER_LINKS;
  for (const auto& [name, library] : libraries) {
    for (const auto& folder : library.folders) {
      ASSERT_TRUE(table.count(folder)) << name << "'s folder " << folder << " is not in the layer table";
      for (const auto& linked : library.links) {
        const auto it = libraries.find(linked);
        if (it == libraries.end()) continue;  // a system library or an imported target
        for (const auto& to : it->second.folders)
          EXPECT_TRUE(allows(table, folder, to)) << name << " (" << folder << ") links " << linked << " (" << to << ")";
      }
    }
  }
}

/// Every library `name` reaches through its links, and the non-hitl ones it reaches.
std::set<std::string> link_closure(const std::map<std::string, LibraryLinks>& libraries, const std::string& name) {
  std::set<std::string> seen;
  std::vector<std::string> todo = {name};
  while (!todo.empty()) {
    const std::string next = todo.back();
    todo.pop_back();
    if (!seen.insert(next).second) continue;
    if (const auto it = libraries.find(next); it != libraries.end())
      for (const auto& l : it->second.links) todo.push_back(l);
  }
  return seen;
}

TEST(Layers, BridgeAndDoctorDoNotLinkSimbody) {
  const auto libraries = read_links();
  for (const char* name : {"hitl_bridge", "hitl_doctor", "hitl_inspect", "hitl_vehicle"}) {
    ASSERT_TRUE(libraries.count(name)) << name;
    for (const auto& reached : link_closure(libraries, name)) {
      EXPECT_EQ(reached.find("SimTK"), std::string::npos) << name << " links Simbody through " << reached;
      EXPECT_NE(reached, "hitl_model") << name << " links the Simbody model";
    }
  }
}

}  // namespace
}  // namespace hitl
