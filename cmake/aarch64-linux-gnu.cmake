# Cross-compiling for arm64 (Raspberry Pi 3/4/5 with a 64-bit OS) with Debian's
# cross compiler (crossbuild-essential-arm64) against multiarch :arm64 -dev
# packages, which install beside the host's in /usr/lib/aarch64-linux-gnu.
# scripts/arm64_test.sh installs what this needs and runs the tests under
# qemu-user.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Libraries and CMake packages from the arm64 multiarch directories; headers of
# arch-independent packages (Eigen, CLI11, nlohmann-json) from /usr/include.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
# Programs that run during the build (idlc from cyclonedds-tools) are the host's.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
# pkg-config must see only the arm64 .pc files.
set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig")
# Test programs (and gtest_discover_tests at build time) run under qemu-user;
# -L: the cross toolchain's sysroot for the dynamic loader.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)
