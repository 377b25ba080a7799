// The side an executable was linked for ("student" or "solution"): one tiny
// object per side, so that each lab's main.cpp compiles once. Declared in
// wb/run.h; drivers write `info.side = WB_SIDE;`.
const char* wb_build_side();
const char* wb_build_side() { return WB_BUILD_SIDE; }
