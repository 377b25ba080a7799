// Where this checkout's files are (framework/src/paths.cpp).
#pragma once
#include <string>

namespace wb {

// The folder of the default scenes: <source tree>/scenes.
std::string scenes_dir();

}  // namespace wb
