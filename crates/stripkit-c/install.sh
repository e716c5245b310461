#!/usr/bin/env bash
# Installs the C library built by `cargo build -p stripkit-c --release` under PREFIX:
#   PREFIX/include/stripkit.h
#   PREFIX/lib/libstripkit.so, PREFIX/lib/libstripkit.a
#   PREFIX/lib/pkgconfig/stripkit.pc            (pkg-config stripkit: the shared library)
#   PREFIX/lib/pkgconfig/stripkit-static.pc     (pkg-config stripkit-static: the archive)
#   PREFIX/lib/cmake/stripkit/stripkitConfig.cmake and ...ConfigVersion.cmake
#                                               (find_package(stripkit): stripkit::stripkit, stripkit::stripkit_static)
# Usage: crates/stripkit-c/install.sh PREFIX [PROFILE]   (PROFILE: release (default) or debug)
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 PREFIX [release|debug]" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
prefix=$(mkdir -p "$1" && cd "$1" && pwd)
profile=${2:-release}
target=${CARGO_TARGET_DIR:-$root/target}/$profile
for lib in libstripkit.so libstripkit.a; do
    if [ ! -f "$target/$lib" ]; then
        echo "$target/$lib is missing: run cargo build -p stripkit-c$([ "$profile" = release ] && echo ' --release') first" >&2
        exit 1
    fi
done
version=$(sed -n 's/^version = "\(.*\)"/\1/p' "$root/Cargo.toml" | head -1)
# What the Rust standard library in the archive needs (rustc --print native-static-libs).
static_libs="-lgcc_s -lutil -lrt -lpthread -lm -ldl -lc"

mkdir -p "$prefix/include" "$prefix/lib/pkgconfig" "$prefix/lib/cmake/stripkit"
install -m 644 "$here/include/stripkit.h" "$prefix/include/"
install -m 755 "$target/libstripkit.so" "$prefix/lib/"
install -m 644 "$target/libstripkit.a" "$prefix/lib/"

cat >"$prefix/lib/pkgconfig/stripkit.pc" <<PC
prefix=$prefix
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: stripkit
Description: Triangle strips (C API of the stripkit Rust library)
Version: $version
Cflags: -I\${includedir}
Libs: -L\${libdir} -lstripkit
Libs.private: $static_libs
PC

# The archive on its own: pkg-config stripkit-static (a linker prefers the .so of -lstripkit).
cat >"$prefix/lib/pkgconfig/stripkit-static.pc" <<PC
prefix=$prefix
libdir=\${prefix}/lib
includedir=\${prefix}/include

Name: stripkit-static
Description: Triangle strips (C API of the stripkit Rust library), static archive
Version: $version
Cflags: -I\${includedir}
Libs: \${libdir}/libstripkit.a $static_libs
PC

cat >"$prefix/lib/cmake/stripkit/stripkitConfig.cmake" <<'CMAKE'
# find_package(stripkit) for the stripkit C API: imported targets stripkit::stripkit
# (shared library) and stripkit::stripkit_static (archive, with the system libraries
# the Rust standard library needs).
get_filename_component(_stripkit_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
if(NOT TARGET stripkit::stripkit)
    add_library(stripkit::stripkit SHARED IMPORTED)
    set_target_properties(stripkit::stripkit PROPERTIES
        IMPORTED_LOCATION "${_stripkit_prefix}/lib/libstripkit.so"
        IMPORTED_NO_SONAME TRUE
        INTERFACE_INCLUDE_DIRECTORIES "${_stripkit_prefix}/include")
    add_library(stripkit::stripkit_static STATIC IMPORTED)
    set_target_properties(stripkit::stripkit_static PROPERTIES
        IMPORTED_LOCATION "${_stripkit_prefix}/lib/libstripkit.a"
        INTERFACE_INCLUDE_DIRECTORIES "${_stripkit_prefix}/include"
        INTERFACE_LINK_LIBRARIES "gcc_s;util;rt;pthread;m;dl;c")
endif()
set(stripkit_INCLUDE_DIRS "${_stripkit_prefix}/include")
set(stripkit_LIBRARIES stripkit::stripkit)
unset(_stripkit_prefix)
CMAKE

cat >"$prefix/lib/cmake/stripkit/stripkitConfigVersion.cmake" <<CMAKE
# Compatible when the major version matches (0.x: the minor too) and the one asked for is not newer.
set(PACKAGE_VERSION "$version")
string(REPLACE "." ";" _have "\${PACKAGE_VERSION}")
string(REPLACE "." ";" _want "\${PACKAGE_FIND_VERSION}")
list(GET _have 0 _have_major)
list(GET _have 1 _have_minor)
set(PACKAGE_VERSION_COMPATIBLE FALSE)
if(PACKAGE_FIND_VERSION_MAJOR STREQUAL _have_major AND NOT PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION
   AND (NOT _have_major STREQUAL "0" OR "\${PACKAGE_FIND_VERSION_MINOR}" STREQUAL "" OR PACKAGE_FIND_VERSION_MINOR STREQUAL _have_minor))
    set(PACKAGE_VERSION_COMPATIBLE TRUE)
endif()
if(PACKAGE_FIND_VERSION STREQUAL PACKAGE_VERSION)
    set(PACKAGE_VERSION_EXACT TRUE)
endif()
CMAKE
echo "installed stripkit $version ($profile) under $prefix"
