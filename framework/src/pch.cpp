// Compiled only to make the precompiled headers that other targets reuse
// (cmake/labs.cmake, wb_use_pch).
