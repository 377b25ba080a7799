// Where this checkout's scenes are: the one fact of the framework that depends
// on where the source tree sits, so it is compiled in every build (a one-line
// file) and never shipped precompiled with the rest (cmake/prebuilt.cmake).
#include <string>

#include "wb/paths.h"

namespace wb {

std::string scenes_dir() { return WB_SCENES_DIR; }

}  // namespace wb
