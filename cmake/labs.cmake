# How a lab is built. A lab is registered with one line in CMakeLists.txt,
#   wb_lab(<lab> [DEPS <lab>...])
# and is made of these folders (docs/grading.md, "Adding a lab"):
#   labs/<lab>/*.h, *.cpp        the student's files (the .cpp are the skeletons)
#   solutions/<lab>/*.cpp        the same .cpp files, completed (instructors only)
#   framework/drivers/<lab>/     main.cpp (the executable) and the lab's glue:
#                                which scene keys call which student function
#   tests/<lab>/*.cpp            graded tests
#   scenes/<lab>/*.json          default scenes
# A lab listed in DEPS lends its glue and its student functions of the same
# side (the euler executable runs its scenes with the forces lab's forces).
#
# Targets for side "student" (labs/) and "solution" (solutions/):
#   <lab>_<side>      static library of the student functions
#   <lab>_glue        static library of the glue (compiled once, side-free)
#   <lab>[-solution]  the executable
#   <lab>[-solution]-tests  the graded tests; each test file compiles once
#                     (<lab>_tests_obj) and links against either side

function(wb_lab lab)
  cmake_parse_arguments(A "" "" "DEPS" ${ARGN})
  set_property(GLOBAL APPEND PROPERTY WB_REGISTERED_LABS ${lab})
  set_property(GLOBAL PROPERTY WB_LAB_DEPS_${lab} ${A_DEPS})
endfunction()

function(wb_lab_deps lab out)
  get_property(deps GLOBAL PROPERTY WB_LAB_DEPS_${lab})
  set(${out} ${deps} PARENT_SCOPE)
endfunction()

function(wb_side_dir side out)
  if(side STREQUAL "student")
    set(${out} ${CMAKE_SOURCE_DIR}/labs PARENT_SCOPE)
  else()
    set(${out} ${CMAKE_SOURCE_DIR}/solutions PARENT_SCOPE)
  endif()
endfunction()

function(wb_suffix side out)
  if(side STREQUAL "student")
    set(${out} "" PARENT_SCOPE)
  else()
    set(${out} "-${side}" PARENT_SCOPE)
  endif()
endfunction()

# The library of one lab's student functions on one side.
function(wb_lab_library lab side)
  set(target ${lab}_${side})
  if(TARGET ${target})
    return()
  endif()
  wb_side_dir(${side} dir)
  # The file list is the student's: the same names on both sides.
  file(GLOB student_files CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/labs/${lab}/*.cpp)
  set(sources)
  foreach(f IN LISTS student_files)
    get_filename_component(name ${f} NAME)
    if(NOT EXISTS ${dir}/${lab}/${name})
      message(FATAL_ERROR "${dir}/${lab}/${name} is missing (labs/${lab}/${name} has no counterpart)")
    endif()
    list(APPEND sources ${dir}/${lab}/${name})
  endforeach()
  add_library(${target} STATIC ${sources})
  target_include_directories(${target} PUBLIC ${CMAKE_SOURCE_DIR}/labs/${lab})
  target_link_libraries(${target} PUBLIC wb_core)
  wb_lab_deps(${lab} deps)
  foreach(dep IN LISTS deps)
    wb_lab_library(${dep} ${side})
    target_link_libraries(${target} PUBLIC ${dep}_${side})
  endforeach()
endfunction()

# The glue of one lab: every .cpp in framework/drivers/<lab>/ but main.cpp.
# It calls the student functions through labs/<lab>/*.h only, so it compiles
# once; the executable links it before the side's library.
function(wb_lab_glue lab out)
  set(target ${lab}_glue)
  if(NOT TARGET ${target})
    set(glue_dir ${CMAKE_SOURCE_DIR}/framework/drivers/${lab})
    file(GLOB glue CONFIGURE_DEPENDS ${glue_dir}/*.cpp)
    list(FILTER glue EXCLUDE REGEX "/main\\.cpp$")
    if(glue)
      add_library(${target} STATIC ${glue})
    else()
      add_library(${target} INTERFACE)
    endif()
    get_target_property(type ${target} TYPE)
    set(scope PUBLIC)
    if(type STREQUAL "INTERFACE_LIBRARY")
      set(scope INTERFACE)
    endif()
    target_include_directories(${target} ${scope} ${glue_dir} ${CMAKE_SOURCE_DIR}/labs/${lab})
    target_link_libraries(${target} ${scope} wb_run)
    wb_lab_deps(${lab} deps)
    foreach(dep IN LISTS deps)
      wb_lab_glue(${dep} dep_glue)
      target_link_libraries(${target} ${scope} ${dep_glue})
    endforeach()
  endif()
  set(${out} ${target} PARENT_SCOPE)
endfunction()

function(wb_add_lab lab side)
  wb_lab_library(${lab} ${side})
  wb_lab_glue(${lab} glue)
  wb_suffix(${side} suffix)
  set(exe ${lab}${suffix})
  add_executable(${exe} ${CMAKE_SOURCE_DIR}/framework/drivers/${lab}/main.cpp)
  # Glue first, then the side's student functions it calls.
  target_link_libraries(${exe} PRIVATE ${glue} ${lab}_${side} wb_run wb_core)
  target_compile_definitions(${exe} PRIVATE WB_LAB="${lab}" WB_SIDE="${side}")

  if(NOT WB_TESTS)
    return()
  endif()
  file(GLOB test_sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/${lab}/*.cpp)
  if(NOT test_sources)
    return()
  endif()
  # The test files compile once, whichever sides are built.
  if(NOT TARGET ${lab}_tests_obj)
    add_library(${lab}_tests_obj OBJECT ${test_sources})
    target_include_directories(${lab}_tests_obj PRIVATE ${CMAKE_SOURCE_DIR}/tests/common
                                                        ${CMAKE_SOURCE_DIR}/tests/${lab})
    target_link_libraries(${lab}_tests_obj PRIVATE ${glue} wb_core Catch2::Catch2)
    # The lab's headers (and its dependencies'), without linking a side.
    target_include_directories(${lab}_tests_obj PRIVATE ${CMAKE_SOURCE_DIR}/labs/${lab})
    wb_lab_deps(${lab} deps)
    foreach(dep IN LISTS deps)
      target_include_directories(${lab}_tests_obj PRIVATE ${CMAKE_SOURCE_DIR}/labs/${dep})
    endforeach()
  endif()
  set(tests ${lab}${suffix}-tests)
  add_executable(${tests} $<TARGET_OBJECTS:${lab}_tests_obj>)
  target_link_libraries(${tests} PRIVATE ${glue} ${lab}_${side} wb_run wb_core
                                         Catch2::Catch2WithMain)
  catch_discover_tests(${tests}
    TEST_PREFIX "${side}/"
    EXTRA_ARGS -w NoTests
    TEST_LIST ${tests}_TESTS)
  # Labels and a time limit for every discovered test. A list passed through
  # catch_discover_tests' PROPERTIES is flattened ("LABELS forces solution"
  # sets one label), so they are set here, from the list Catch's generated
  # file defines; CTest reads this file after Catch's.
  set(labels_file ${CMAKE_CURRENT_BINARY_DIR}/${tests}_labels.cmake)
  file(WRITE ${labels_file}
    "foreach(t IN LISTS ${tests}_TESTS)\n"
    "  set_tests_properties(\"\${t}\" PROPERTIES LABELS \"${lab};${side}\" TIMEOUT 120)\n"
    "endforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels_file})
endfunction()
