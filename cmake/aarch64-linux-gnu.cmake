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
# Test programs (and gtest_discover_tests at build time) run under qemu-user,
# with the dynamic loader and libc of libc6:arm64 (/lib/ld-linux-aarch64.so.1,
# installed with the :arm64 -dev packages). Not -L /usr/aarch64-linux-gnu: its
# loader (libc6-arm64-cross) is another glibc build than the libc.so.6 it then
# loads from /lib/aarch64-linux-gnu, and with the two mixed a program hangs
# when it starts its first thread.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64)
# Arm64 libraries unpacked outside the multiarch directories (the script's
# BUILD_DIR/sysroot-extra: glog, gflags) go on LD_LIBRARY_PATH inside the
# emulator: a program's RUNPATH finds libglog but not the libgflags libglog
# needs.
if(DSSWARM_ARM64_LIBRARY_PATH)
  list(APPEND CMAKE_CROSSCOMPILING_EMULATOR -E LD_LIBRARY_PATH=${DSSWARM_ARM64_LIBRARY_PATH})
endif()
