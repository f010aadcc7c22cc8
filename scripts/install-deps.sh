#!/usr/bin/env bash
# Installs everything hitl needs to build and test, from Debian/Ubuntu packages (--test: the tests'
# tools too; --px4: also what scripts/px4-sitl.sh needs to build PX4 SITL).
# Debian 12 and Ubuntu 24.04. Uses sudo when not root.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake ccache pkg-config
  libcli11-dev libeigen3-dev libsimbody-dev libncurses-dev nlohmann-json3-dev
  libpugixml-dev libgeographiclib-dev libedit-dev
  libtomlplusplus-dev libsqlite3-dev  # hitl campaign: its TOML files and its history database (docs/campaigns.md)
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox
  # hitl report's interactive page inlines Debian's dygraphs (docs/report.md); without it the static page
  libjs-dygraphs
)
if [ "${1:-}" = "--test" ]; then
  # Tests also use: clang + its sanitizer/fuzzer runtime (libFuzzer), node + npm (node-mavlink conformance),
  # tmux (terminal UI end-to-end), shellcheck (board scripts), g++-aarch64-linux-gnu and file (the
  # arm64 board packages, test label "package"), ninja-build (the PX4 glue's stand-in check with PX4's
  # usual generator, tests/target).
  packages+=(clang libclang-rt-dev tmux shellcheck g++-aarch64-linux-gnu file ninja-build)
  # Completions, man page and .deb (tests/completions, tests/cmake): zsh and fish run the completion scripts,
  # groff-base, man-db and mandoc render and lint the man page, dpkg-dev's dpkg-shlibdeps computes
  # the package's Depends (file finds the binaries for it).
  packages+=(zsh fish groff-base man-db mandoc dpkg-dev)
  # hitl campaign slurm against a real Slurm that the test starts (tests/cli/campaign_slurm_test.cpp):
  # Debian's Slurm (controller, node daemon, client) and munge, its authentication.
  packages+=(slurm-wlm munge)
  # hitl report's page rendered in headless Chromium (tests/cli/report_e2e_test.cpp).
  # Ubuntu ships Chromium only as a snap (its deb is a stub that installs the snap): there the test
  # skips outside CI instead; Debian's deb is the browser itself.
  if ! grep -qs '^ID=ubuntu' /etc/os-release; then packages+=(chromium); fi
  # hitl campaign's JUnit XML read back by a real consumer (tests/cli/campaign_e2e_test.cpp).
  packages+=(python3-junitparser)
  command -v node >/dev/null 2>&1 || packages+=(nodejs)
  command -v npm >/dev/null 2>&1 || packages+=(npm)
fi
if [ "${1:-}" = "--px4" ]; then
  # PX4 v1.16.0 SITL's build (scripts/px4-sitl.sh): Debian's Python packages PX4's generators use,
  # Ninja, and git for PX4's version script.
  packages+=(python3-empy python3-jinja2 python3-kconfiglib python3-jsonschema python3-future
             python3-packaging python3-genmsg python3-numpy ninja-build g++ git)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}" >&2
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
