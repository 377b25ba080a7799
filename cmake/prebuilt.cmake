# The student pack's prebuilt framework.
#
# Students never edit the framework (wb_core, wb_run), the labs' glue or the
# drivers' main.cpp, yet compiling them is most of a fresh build. tools/pack
# compiles them once when it makes the pack and ships them in prebuilt/ with a
# manifest, prebuilt/manifest.cmake:
#   WB_PREBUILT_KEY      the toolchain they were compiled with (wb_toolchain_key)
#   WB_PREBUILT_SOURCES  path;sha256;path;sha256;... of every file under
#                        framework/ and every labs/<lab>/*.h (the glue includes
#                        the lab's headers)
#   WB_PREBUILT_PARTS    kind;target;file;... (kind: lib or obj)
# A build uses them only when its own key is the same and every one of those
# files is unchanged (and none was added); otherwise it compiles them from
# source, exactly as an instructor checkout always does, and says why at
# configure time. WB_PREBUILT=OFF never uses them. The one per-checkout fact,
# where the scenes are, is always compiled (framework/src/paths.cpp), and so
# is framework/src/side.cpp.

option(WB_PREBUILT "Use prebuilt/ (the student pack's compiled framework) when it matches this toolchain and the framework's files" ON)
option(WB_PREBUILT_EXPORT "Write wb-prebuilt.txt: what tools/pack ships from this build as prebuilt/" OFF)

set(WB_PREBUILT_DIR ${CMAKE_SOURCE_DIR}/prebuilt)

# What decides whether compiled objects can be reused: the compiler, the
# target, the build type and flags, the language standard, and the header
# libraries the framework compiles against (and whether the implicit glue
# was compiled with CHOLMOD: cmake/cholmod.cmake).
function(wb_toolchain_key out)
  string(TOUPPER "${CMAKE_BUILD_TYPE}" config)
  set(${out}
      "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION} | ${CMAKE_SYSTEM_NAME} ${CMAKE_SYSTEM_PROCESSOR} | build type '${CMAKE_BUILD_TYPE}' | flags '${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${config}}' | C++${CMAKE_CXX_STANDARD} | Eigen ${Eigen3_VERSION} | nlohmann_json ${nlohmann_json_VERSION} | CLI11 ${CLI11_VERSION} | CHOLMOD ${WB_CHOLMOD_FOUND} | hardened ${WB_HARDENED}"
      PARENT_SCOPE)
endfunction()

# Every file the prebuilt parts were compiled from, relative to the source tree.
function(wb_prebuilt_inputs out)
  file(GLOB_RECURSE framework_files CONFIGURE_DEPENDS RELATIVE ${CMAKE_SOURCE_DIR}
       ${CMAKE_SOURCE_DIR}/framework/*)
  file(GLOB lab_headers CONFIGURE_DEPENDS RELATIVE ${CMAKE_SOURCE_DIR}
       ${CMAKE_SOURCE_DIR}/labs/*/*.h)
  set(files ${framework_files} ${lab_headers})
  list(SORT files)
  set(${out} ${files} PARENT_SCOPE)
endfunction()

# Sets WB_USE_PREBUILT (TRUE/FALSE) and WB_PREBUILT_PART_<target> for each
# shipped part, and says at configure time which way it went and why.
function(wb_prebuilt_decide)
  set(use FALSE)
  set(why "")
  if(NOT EXISTS ${WB_PREBUILT_DIR}/manifest.cmake)
    set(WB_USE_PREBUILT FALSE PARENT_SCOPE)
    return()  # an instructor checkout: nothing to say
  endif()
  if(NOT WB_PREBUILT)
    set(why "WB_PREBUILT is OFF")
  else()
    include(${WB_PREBUILT_DIR}/manifest.cmake)
    wb_toolchain_key(key)
    wb_prebuilt_inputs(inputs)
    # Editing any of them reconfigures, and so decides again.
    set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
                 ${WB_PREBUILT_DIR}/manifest.cmake)
    foreach(f IN LISTS inputs)
      set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
                   ${CMAKE_SOURCE_DIR}/${f})
    endforeach()
    if(NOT key STREQUAL WB_PREBUILT_KEY)
      set(why "this toolchain is [${key}], the pack's was [${WB_PREBUILT_KEY}]")
    else()
      set(recorded)
      set(rest ${WB_PREBUILT_SOURCES})
      while(rest AND NOT why)
        list(POP_FRONT rest f sha)
        list(APPEND recorded ${f})
        if(NOT EXISTS ${CMAKE_SOURCE_DIR}/${f})
          set(why "${f} was removed")
        else()
          file(SHA256 ${CMAKE_SOURCE_DIR}/${f} now)
          if(NOT now STREQUAL sha)
            set(why "${f} changed")
          endif()
        endif()
      endwhile()
      if(NOT why)
        foreach(f IN LISTS inputs)
          if(NOT f IN_LIST recorded)
            set(why "${f} is new")
            break()
          endif()
        endforeach()
      endif()
      set(rest ${WB_PREBUILT_PARTS})
      while(rest AND NOT why)
        list(POP_FRONT rest kind target file)
        if(NOT EXISTS ${WB_PREBUILT_DIR}/${file})
          set(why "prebuilt/${file} is missing")
        endif()
        set(WB_PREBUILT_PART_${target} ${WB_PREBUILT_DIR}/${file} PARENT_SCOPE)
      endwhile()
    endif()
  endif()
  if(why)
    message(STATUS "prebuilt framework: not used (${why}); compiling the framework from source")
    set(WB_USE_PREBUILT FALSE PARENT_SCOPE)
  else()
    message(STATUS "prebuilt framework: used (prebuilt/, compiled when the pack was made; "
                   "-DWB_PREBUILT=OFF compiles it from source)")
    set(WB_USE_PREBUILT TRUE PARENT_SCOPE)
  endif()
endfunction()

# Creates `target` as the shipped part when the prebuilt framework is used.
# Sets ${out} TRUE when it did (the caller then skips compiling it).
function(wb_prebuilt_import target out)
  set(${out} FALSE PARENT_SCOPE)
  if(NOT WB_USE_PREBUILT OR NOT DEFINED WB_PREBUILT_PART_${target})
    return()
  endif()
  set(file ${WB_PREBUILT_PART_${target}})
  if(file MATCHES "\\.a$")
    add_library(${target} STATIC IMPORTED GLOBAL)
    set_target_properties(${target} PROPERTIES IMPORTED_LOCATION ${file})
  else()
    add_library(${target} OBJECT IMPORTED GLOBAL)
    set_target_properties(${target} PROPERTIES IMPORTED_OBJECTS ${file})
  endif()
  set(${out} TRUE PARENT_SCOPE)
endfunction()

# Records a compiled part for WB_PREBUILT_EXPORT (kind: lib or obj).
function(wb_prebuilt_part kind target)
  set_property(GLOBAL APPEND PROPERTY WB_PREBUILT_EXPORT_PARTS ${kind} ${target})
endfunction()

# With WB_PREBUILT_EXPORT: writes <build>/wb-prebuilt.txt, read by tools/pack:
#   key <toolchain key>
#   lib <target> <archive>      obj <target> <object>
# Called at the end of the top CMakeLists.txt, when every part exists.
function(wb_prebuilt_write_export)
  if(NOT WB_PREBUILT_EXPORT)
    return()
  endif()
  if(WB_USE_PREBUILT)
    message(FATAL_ERROR "WB_PREBUILT_EXPORT needs the framework compiled here: add -DWB_PREBUILT=OFF")
  endif()
  wb_toolchain_key(key)
  set(content "key ${key}\n")
  get_property(parts GLOBAL PROPERTY WB_PREBUILT_EXPORT_PARTS)
  while(parts)
    list(POP_FRONT parts kind target)
    if(kind STREQUAL "lib")
      string(APPEND content "lib ${target} $<TARGET_FILE:${target}>\n")
    else()
      string(APPEND content "obj ${target} $<TARGET_OBJECTS:${target}>\n")
    endif()
  endwhile()
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/wb-prebuilt.txt CONTENT "${content}")
endfunction()
