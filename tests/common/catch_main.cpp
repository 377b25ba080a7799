// Catch's main(), compiled here only where Debian's prebuilt one cannot link: a build with
// another standard library than the one libCatch2WithMain.a was compiled with (clang++
// -stdlib=libc++, the library of macOS; CMakeLists.txt, WB_CATCH_MAIN).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
