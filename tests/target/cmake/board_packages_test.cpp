// The board packages, as CI makes them: target/ configured on its own with the arm64 toolchain
// (target/cmake/aarch64-linux-gnu.cmake) in a temporary directory, built, packed by cpack; then
// the two .deb files are checked with dpkg-deb (-c contents, -I control: Architecture, conffiles,
// maintainer scripts) and file (an aarch64 ELF).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/process.h"

namespace hitl {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

struct Shell {
  int code;
  std::string out;
};

/// Runs a shell command line; stdout and stderr together.
Shell sh(const std::string& command, std::chrono::milliseconds timeout = 120s) {
  test::Process p({"/bin/sh", "-c", command + " 2>&1"});
  const int code = p.wait(timeout);
  return {code, p.out()};
}

std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Built {
  std::string dir;          ///< the temporary directory
  std::string build;        ///< the build tree, where cpack leaves the .deb files
  std::string vio_deb;
  std::string scripts_deb;
};

/// Configures, builds and packs target/ for arm64; empty `problem` on success.
Built build_packages(std::string& problem) {
  Built b;
  if (sh("command -v aarch64-linux-gnu-g++").code != 0) {
    problem = "aarch64-linux-gnu-g++ is missing: scripts/install-deps.sh --test installs g++-aarch64-linux-gnu";
    return b;
  }
  b.dir = test::temp_dir();
  b.build = b.dir + "/build";
  const std::string source = std::string(HITL_SOURCE_DIR) + "/target";
  auto step = [&](const std::string& what, const std::string& command, std::chrono::milliseconds timeout) {
    if (!problem.empty()) return;
    const Shell r = sh(command, timeout);
    if (r.code != 0) problem = what + " failed (exit " + std::to_string(r.code) + "):\n" + r.out;
  };
  step("configuring target/ for arm64",
       "cmake -S " + shell_quoted(source) + " -B " + shell_quoted(b.build) + " -DCMAKE_TOOLCHAIN_FILE=" +
           shell_quoted(source + "/cmake/aarch64-linux-gnu.cmake") + " -DCMAKE_BUILD_TYPE=Release",
       300s);
  if (problem.empty()) {
    const Shell r = sh("cmake --build " + shell_quoted(b.build) + " -j2", 1500s);
    if (r.code != 0) problem = "building the board packages failed (exit " + std::to_string(r.code) + "):\n" + r.out;
    // The board build is held to the host build's standard: no warnings.
    if (problem.empty() && r.out.find("warning:") != std::string::npos) problem = "the arm64 build has warnings:\n" + r.out;
  }
  step("cpack", "cd " + shell_quoted(b.build) + " && cpack -G DEB", 300s);
  b.vio_deb = b.build + "/voxl-hitl-vio-server_" + HITL_VERSION + "_arm64.deb";
  b.scripts_deb = b.build + "/voxl-hitl-px4-scripts_" + HITL_VERSION + "_arm64.deb";
  step("extracting " + b.vio_deb, "dpkg-deb -x " + shell_quoted(b.vio_deb) + " " + shell_quoted(b.dir + "/vio"), 60s);
  step("extracting " + b.scripts_deb, "dpkg-deb -x " + shell_quoted(b.scripts_deb) + " " + shell_quoted(b.dir + "/scripts"), 60s);
  return b;
}

void only_the_two_board_packages_are_made(const Built& b) {
  SCOPED_TRACE("the .deb files");
  std::vector<std::string> debs;
  for (const auto& e : fs::directory_iterator(b.build)) {
    if (e.path().extension() == ".deb") debs.push_back(e.path().filename().string());
  }
  std::sort(debs.begin(), debs.end());
  EXPECT_EQ(debs, (std::vector<std::string>{fs::path(b.scripts_deb).filename().string(), fs::path(b.vio_deb).filename().string()}));
}

void vio_server_package_holds_the_server_its_conffile_and_the_unit(const Built& b) {
  SCOPED_TRACE(b.vio_deb);
  const Shell contents = sh("dpkg-deb -c " + shell_quoted(b.vio_deb));
  ASSERT_EQ(contents.code, 0) << contents.out;
  EXPECT_NE(contents.out.find("./usr/bin/voxl-hitl-vio-server"), std::string::npos) << contents.out;
  EXPECT_NE(contents.out.find("./etc/modalai/voxl-hitl-vio-server.conf"), std::string::npos) << contents.out;
  EXPECT_NE(contents.out.find("./lib/systemd/system/voxl-hitl-vio-server.service"), std::string::npos) << contents.out;
  EXPECT_EQ(contents.out.find("/include/"), std::string::npos) << "nothing of the build leaks in";

  const Shell info = sh("dpkg-deb -I " + shell_quoted(b.vio_deb));
  ASSERT_EQ(info.code, 0) << info.out;
  EXPECT_NE(info.out.find("Package: voxl-hitl-vio-server"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("Architecture: arm64"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find(std::string("Version: ") + HITL_VERSION), std::string::npos) << info.out;
  for (const char* member : {"conffiles", "postinst", "prerm", "postrm"}) {
    EXPECT_NE(info.out.find(member), std::string::npos) << member << "\n" << info.out;
  }
  const Shell conffiles = sh("dpkg-deb -I " + shell_quoted(b.vio_deb) + " conffiles");
  EXPECT_EQ(conffiles.out, "/etc/modalai/voxl-hitl-vio-server.conf\n");

  EXPECT_EQ(read_file(b.dir + "/vio/etc/modalai/voxl-hitl-vio-server.conf"),
            read_file(std::string(HITL_SOURCE_DIR) + "/target/vio-server/voxl-hitl-vio-server.conf"));
  EXPECT_NE(read_file(b.dir + "/vio/lib/systemd/system/voxl-hitl-vio-server.service").find("ExecStart=/usr/bin/voxl-hitl-vio-server"),
            std::string::npos);
}

void the_server_is_a_static_arm64_binary(const Built& b) {
  SCOPED_TRACE("file usr/bin/voxl-hitl-vio-server");
  const Shell file = sh("file -b " + shell_quoted(b.dir + "/vio/usr/bin/voxl-hitl-vio-server"));
  ASSERT_EQ(file.code, 0) << file.out;
  EXPECT_NE(file.out.find("ELF 64-bit"), std::string::npos) << file.out;
  EXPECT_NE(file.out.find("ARM aarch64"), std::string::npos) << file.out;
  // Static: it runs on the board's older glibc and libstdc++ (Ubuntu 18.04 on the VOXL2).
  EXPECT_NE(file.out.find("statically linked"), std::string::npos) << file.out;
}

void px4_scripts_package_holds_the_start_script_and_the_generated_parameters(const Built& b) {
  SCOPED_TRACE(b.scripts_deb);
  const Shell contents = sh("dpkg-deb -c " + shell_quoted(b.scripts_deb));
  ASSERT_EQ(contents.code, 0) << contents.out;
  std::string script_line;
  std::istringstream lines(contents.out);
  for (std::string line; std::getline(lines, line);) {
    if (line.size() > 23 && line.compare(line.size() - 23, 23, "./usr/bin/voxl-px4-hitl") == 0) script_line = line;
  }
  EXPECT_EQ(script_line.rfind("-rwxr-xr-x root/root", 0), 0u) << contents.out;
  EXPECT_NE(contents.out.find("./usr/share/voxl-hitl-px4-scripts/voxl-px4-hitl-set-default-parameters.config"),
            std::string::npos)
      << contents.out;

  const Shell info = sh("dpkg-deb -I " + shell_quoted(b.scripts_deb));
  ASSERT_EQ(info.code, 0) << info.out;
  EXPECT_NE(info.out.find("Package: voxl-hitl-px4-scripts"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("Architecture: arm64"), std::string::npos) << info.out;
  const Shell preinst = sh("dpkg-deb -I " + shell_quoted(b.scripts_deb) + " preinst");
  EXPECT_NE(preinst.out.find("--divert /usr/bin/voxl-px4-hitl.voxl-px4 /usr/bin/voxl-px4-hitl"), std::string::npos)
      << preinst.out;

  EXPECT_EQ(read_file(b.dir + "/scripts/usr/bin/voxl-px4-hitl"),
            read_file(std::string(HITL_SOURCE_DIR) + "/target/px4/scripts/voxl-px4-hitl"));
  EXPECT_EQ(read_file(b.dir + "/scripts/usr/share/voxl-hitl-px4-scripts/voxl-px4-hitl-set-default-parameters.config"),
            read_file(HITL_PX4_DEFAULTS_CONFIG));
}

// One test, so the arm64 build (minutes on 2 cores) happens once.
TEST(BoardPackages, BothArm64PackagesAreBuiltWithTheirContents) {
  std::string problem;
  const Built b = build_packages(problem);
  ASSERT_TRUE(problem.empty()) << problem;
  only_the_two_board_packages_are_made(b);
  vio_server_package_holds_the_server_its_conffile_and_the_unit(b);
  the_server_is_a_static_arm64_binary(b);
  px4_scripts_package_holds_the_start_script_and_the_generated_parameters(b);
}

}  // namespace
}  // namespace hitl
