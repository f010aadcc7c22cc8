// Installing: `cmake --install` of component hitl into a temporary DESTDIR puts every file in its
// standard place and the installed hitl runs; `cpack` builds the .deb `hitl` whose Depends are
// Debian runtime packages and which holds component hitl only (no board package files).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "tests/support/tools.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

const std::vector<std::string>& installed_files() {
  static const std::vector<std::string> files{
      "usr/bin/hitl",
      "usr/share/bash-completion/completions/hitl",
      "usr/share/zsh/vendor-completions/_hitl",
      "usr/share/fish/vendor_completions.d/hitl.fish",
      "usr/share/man/man1/hitl.1",
      "usr/share/doc/hitl/README.md",
      "usr/share/doc/hitl/guide.md",
      "usr/share/doc/hitl/config.md",
      "usr/share/doc/hitl/engine.md",
      "usr/share/doc/hitl/allan-icm-42688-p-gyro.svg",  // the images the pages show, beside them
      "usr/share/doc/hitl/report-demo.png",
      "usr/share/doc/hitl/examples/hover.json",
      "usr/share/doc/hitl/examples/square.json",
      "usr/share/doc/hitl/examples/figure-eight.json",
      "usr/share/doc/hitl/examples/yaw-spin.json",
      "usr/share/doc/hitl/examples/hitl.toml",
      "usr/share/doc/hitl/examples/phase1-check.sh"};
  return files;
}

bool executable(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && (st.st_mode & S_IXOTH) != 0;
}

TEST(Install, CmakeInstallPutsEveryFileInItsPlaceAndTheBinaryRuns) {
  const auto destdir = test::temp_dir();
  const auto r = test::run_program({"/usr/bin/env", "DESTDIR=" + destdir, "cmake", "--install", HITL_BUILD_DIR, "--prefix",
                                    "/usr", "--component", "hitl"},
                                   300s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  for (const auto& f : installed_files()) EXPECT_TRUE(std::filesystem::exists(destdir + "/" + f)) << f;
  EXPECT_TRUE(executable(destdir + "/usr/bin/hitl"));
  EXPECT_TRUE(executable(destdir + "/usr/share/doc/hitl/examples/phase1-check.sh"));
  for (const auto& entry : std::filesystem::recursive_directory_iterator(destdir))
    EXPECT_EQ(entry.path().string().find("/voxl-"), std::string::npos) << "a board file in the host install: " << entry.path();

  const auto version = test::run_program({destdir + "/usr/bin/hitl", "--version"});
  EXPECT_EQ(version.exit_code, 0) << version.err;
  EXPECT_EQ(version.out.rfind("hitl ", 0), 0u) << version.out;
  // The installed completions are the installed binary's.
  const auto bash = test::run_program({destdir + "/usr/bin/hitl", "completion", "bash"});
  EXPECT_EQ(bash.out, test::read_text(destdir + "/usr/share/bash-completion/completions/hitl"));
}

TEST(Install, CpackBuildsTheHostDebWithDebianDepends) {
  if (test::find_program("dpkg-deb").empty() || test::find_program("dpkg-shlibdeps").empty())
    GTEST_SKIP() << "dpkg-dev is not installed (scripts/install-deps.sh --test)";
  const auto out = test::temp_dir();
  const auto r = test::run_program({"cpack", "--config", std::string(HITL_BUILD_DIR) + "/CPackConfig.cmake", "-G", "DEB", "-B", out}, 600s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  std::vector<std::string> debs;
  for (const auto& entry : std::filesystem::directory_iterator(out))
    if (entry.path().extension() == ".deb") debs.push_back(entry.path().string());
  ASSERT_EQ(debs.size(), 1u) << "one host package expected; cpack said:\n" << r.out;
  EXPECT_NE(debs[0].find("/hitl_"), std::string::npos) << debs[0];

  const auto info = test::run_program({"dpkg-deb", "--field", debs[0], "Package", "Version", "Architecture", "Depends"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("Package: hitl\n"), std::string::npos) << info.out;
  const auto depends_at = info.out.find("Depends: ");
  ASSERT_NE(depends_at, std::string::npos) << info.out;
  const auto depends = info.out.substr(depends_at);
  // What the binary links, as Debian packages (found by dpkg-shlibdeps, versioned).
  for (const char* package : {"libc6 (>=", "libstdc++6 (>=", "libsimbody", "libedit2"})  // libedit: hitl shell's line editing
    EXPECT_NE(depends.find(package), std::string::npos) << package << " missing from " << depends;

  const auto contents = test::run_program({"dpkg-deb", "--contents", debs[0]});
  ASSERT_EQ(contents.exit_code, 0) << contents.err;
  for (const auto& f : installed_files()) EXPECT_NE(contents.out.find("./" + f + "\n"), std::string::npos) << f;
  // Board files are named voxl-* (voxl-px4-hitl, voxl-hitl-vio-server); an example vehicle file may
  // name the board it models (examples/vehicles/x500-voxl2-icm-42688-p.json).
  EXPECT_EQ(contents.out.find("/voxl-"), std::string::npos) << contents.out;

  // The packaged binary runs and reports the package's version.
  const auto unpacked = out + "/root";
  ASSERT_EQ(test::run_program({"dpkg-deb", "-x", debs[0], unpacked}).exit_code, 0);
  const auto version = test::run_program({unpacked + "/usr/bin/hitl", "--version"});
  EXPECT_EQ(version.exit_code, 0) << version.err;
  const auto field = test::run_program({"dpkg-deb", "--field", debs[0], "Version"});
  EXPECT_EQ("hitl " + field.out, version.out);
}

}  // namespace
}  // namespace hitl
