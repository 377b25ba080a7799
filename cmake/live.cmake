# The live pages' WebAssembly build (docs/live.md). tools/view --live configures it
# with emscripten's CMake (emcmake cmake -DWB_LIVE=ON) in build/live/; CMakeLists.txt
# includes this file and stops after it. Each lab and side becomes one JavaScript
# module with its WebAssembly inside, <lab>[-solution]-live.js, compiled by em++ from
# the same files as the native executable: the lab's main.cpp (main renamed, so that
# the page calls it to learn the lab's LabInfo), its glue, the side's student files and
# the framework, plus the live layer (framework/live/: what the page calls). A lab
# whose state is not particles has its own live layer in framework/drivers/<lab>/live/.
if(NOT EMSCRIPTEN)
  message(FATAL_ERROR "WB_LIVE: configure with emscripten (emcmake cmake -DWB_LIVE=ON ...): "
                      "tools/view --live does it")
endif()

# Header-only libraries come from the host (Debian's packages): emscripten's toolchain
# looks for packages in its own sysroot only unless told otherwise.
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
# nlohmann-json and CLI11 live in /usr/include, which must not be on em++'s include
# path (the host's C library is there): each is reached through a folder of its own.
set(_wb_shim ${CMAKE_BINARY_DIR}/host-include)
foreach(lib IN ITEMS nlohmann CLI)
  find_path(_wb_${lib}_dir ${lib} PATHS /usr/include NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH)
  if(NOT _wb_${lib}_dir)
    message(FATAL_ERROR "WB_LIVE: /usr/include/${lib} not found (Debian packages "
                        "nlohmann-json3-dev, libcli11-dev)")
  endif()
  file(MAKE_DIRECTORY ${_wb_shim})
  file(CREATE_LINK ${_wb_${lib}_dir}/${lib} ${_wb_shim}/${lib} SYMBOLIC)
endforeach()
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED)
set_target_properties(nlohmann_json::nlohmann_json PROPERTIES
                      INTERFACE_INCLUDE_DIRECTORIES ${_wb_shim})
add_library(CLI11::CLI11 INTERFACE IMPORTED)
set_target_properties(CLI11::CLI11 PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${_wb_shim})

set(WB_CHOLMOD OFF CACHE BOOL "" FORCE)  # SuiteSparse is a native library
include(cmake/cholmod.cmake)
include(cmake/prebuilt.cmake)
set(WB_USE_PREBUILT FALSE)
set(WB_TESTS OFF)
add_compile_options(-Wall -Wextra)
# C++ exceptions carry a bad scene, a refused knob or a work overrun to the page as a
# message (wb::InputError). Emscripten's exceptions are JavaScript's: a function compiled
# to catch them calls every callee through JavaScript, which would make the step several
# times slower. So only the files that catch are compiled to (the page's entry points,
# and the JSON reader, which words the parser's errors); a throw from any other file
# unwinds through it to the entry point's catch (its destructors do not run: the run that
# threw is loaded again before it steps again). The link takes the runtime that catches.
add_link_options(-fexceptions)

add_subdirectory(framework)
# (Without the precompiled header: it was compiled not to catch.)
set_source_files_properties(${CMAKE_SOURCE_DIR}/framework/src/input.cpp
                            DIRECTORY ${CMAKE_SOURCE_DIR}/framework
                            PROPERTIES COMPILE_OPTIONS -fexceptions SKIP_PRECOMPILE_HEADERS ON)
set_source_files_properties(${CMAKE_SOURCE_DIR}/framework/live/exports.cpp
                            PROPERTIES COMPILE_OPTIONS -fexceptions SKIP_PRECOMPILE_HEADERS ON)

# The live layer shared by every lab: the registry, the run contract's bookkeeping of
# a live run, and the functions the page calls (objects: nothing in the lab calls them,
# so a library's would be left out of the link).
add_library(wb_live OBJECT ${CMAKE_SOURCE_DIR}/framework/live/live.cpp
                           ${CMAKE_SOURCE_DIR}/framework/live/exports.cpp)
target_include_directories(wb_live PUBLIC ${CMAKE_SOURCE_DIR}/framework/live)
target_link_libraries(wb_live PUBLIC wb_core)
wb_use_pch(wb_live)

# What the page calls (framework/live/exports.cpp) and the runtime it needs.
set(WB_LIVE_LINK_OPTIONS
    -sSINGLE_FILE=1 -sMODULARIZE=1 -sEXPORT_NAME=wbLiveModule -sALLOW_MEMORY_GROWTH=1
    -sENVIRONMENT=web,node -sINITIAL_MEMORY=33554432
    "-sEXPORTED_RUNTIME_METHODS=['ccall','cwrap','UTF8ToString']")

function(wb_add_live lab side)
  wb_lab_library(${lab} ${side})
  wb_lab_glue(${lab} glue)
  wb_suffix(${side} suffix)
  if(NOT TARGET ${lab}_live_main)
    # main.cpp as the native build compiles it, main renamed: the page calls it once.
    add_library(${lab}_live_main OBJECT ${CMAKE_SOURCE_DIR}/framework/drivers/${lab}/main.cpp)
    target_link_libraries(${lab}_live_main PRIVATE ${glue} wb_core)
    # (No precompiled header: it was compiled without that definition.)
    target_compile_definitions(${lab}_live_main PRIVATE WB_LAB="${lab}"
                               WB_SIDE=wb_build_side\(\) main=wb_live_lab_main)
  endif()
  if(NOT TARGET wb_side_${side})
    add_library(wb_side_${side} OBJECT ${CMAKE_SOURCE_DIR}/framework/src/side.cpp)
    target_compile_definitions(wb_side_${side} PRIVATE WB_BUILD_SIDE="${side}")
  endif()
  # The lab's own live layer, or the particle labs' (it replaces the run contract's
  # run_particle_lab: an object, so that it is linked before the library's).
  file(GLOB own CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/framework/drivers/${lab}/live/*.cpp)
  if(NOT own)
    set(own ${CMAKE_SOURCE_DIR}/framework/live/particle_live.cpp)
  endif()
  set(exe ${lab}${suffix}-live)
  add_executable(${exe} $<TARGET_OBJECTS:${lab}_live_main> $<TARGET_OBJECTS:wb_side_${side}>
                        $<TARGET_OBJECTS:wb_live> ${own})
  wb_lab_link_items(${lab} ${side} link_items)
  target_include_directories(${exe} PRIVATE ${CMAKE_SOURCE_DIR}/framework/live)
  target_link_libraries(${exe} PRIVATE ${link_items} wb_run wb_core)
  wb_use_pch(${exe})
  set_target_properties(${exe} PROPERTIES SUFFIX ".js")
  target_link_options(${exe} PRIVATE ${WB_LIVE_LINK_OPTIONS})
endfunction()

wb_sides(_sides)
get_property(_wb_labs GLOBAL PROPERTY WB_REGISTERED_LABS)
foreach(lab IN LISTS _wb_labs)
  if(EXISTS ${CMAKE_SOURCE_DIR}/labs/${lab} AND
     EXISTS ${CMAKE_SOURCE_DIR}/framework/drivers/${lab}/main.cpp)
    foreach(side IN LISTS _sides)
      wb_add_live(${lab} ${side})
    endforeach()
  endif()
endforeach()
