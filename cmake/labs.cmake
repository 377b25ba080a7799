# How a lab is built. A lab is registered with one line in CMakeLists.txt,
#   wb_lab(<lab> [DEPS <lab>...] [TESTS_USE_GLUE] [TEST_UNITS n])
# and is made of these folders:
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
#   <lab>[-solution]-tests  the graded tests; a lab's test files compile once,
#                     as one unit (<lab>_tests_obj), and link against either
#                     side. They see the framework's headers only (wb_headers)
#                     and link the lab's glue and the run contract only with
#                     TESTS_USE_GLUE, so that the grader's scratch build of a
#                     lab compiles the lab and its tests, nothing else.

# Precompiled headers: Eigen and nlohmann-json (and Catch for the tests) are
# parsed once per build instead of once per file. Targets reuse one PCH each:
# wb_pch (framework), wb_lab_pch (the student functions: Eigen alone, since a
# PCH's inline functions cost every file that loads it) and wb_tests_pch.
# CLI11 is in none: its static objects would be compiled into every file; only
# framework/src/cli.cpp includes it. GCC ignores a PCH it cannot use, so this
# only ever saves time. WB_PCH=OFF turns it off.
# A hardened build (WB_HARDENED) puts wb/hardened.h first in every precompiled header, or
# force-includes it where there is none: it must precede Eigen everywhere.
function(wb_use_pch target)
  set(first)
  if(WB_HARDENED)
    set(first ${CMAKE_SOURCE_DIR}/framework/include/wb/hardened.h)
  endif()
  if(NOT WB_PCH)
    if(first)
      target_compile_options(${target} PRIVATE -include ${first})
    endif()
    return()
  endif()
  if(ARGN STREQUAL "LAB")
    set(pch wb_lab_pch)
    if(NOT TARGET ${pch})
      add_library(${pch} OBJECT ${CMAKE_SOURCE_DIR}/framework/src/pch.cpp)
      target_link_libraries(${pch} PRIVATE Eigen3::Eigen)
      target_precompile_headers(${pch} PRIVATE ${first} <Eigen/Core> <Eigen/Geometry> <Eigen/Sparse>
                                               <cmath> <vector> <algorithm>)
    endif()
  elseif(ARGN STREQUAL "TESTS")
    set(pch wb_tests_pch)
    if(NOT TARGET ${pch})
      add_library(${pch} OBJECT ${CMAKE_SOURCE_DIR}/framework/src/pch.cpp)
      target_link_libraries(${pch} PRIVATE Eigen3::Eigen Catch2::Catch2)
      target_precompile_headers(${pch} PRIVATE ${first} <catch2/catch.hpp> <Eigen/Core> <cmath> <vector>
                                               <string> <sstream>)
    endif()
  else()
    set(pch wb_pch)
    if(NOT TARGET ${pch})
      add_library(${pch} OBJECT ${CMAKE_SOURCE_DIR}/framework/src/pch.cpp)
      target_link_libraries(${pch} PRIVATE Eigen3::Eigen nlohmann_json::nlohmann_json)
      target_precompile_headers(${pch} PRIVATE ${first} <Eigen/Core> <nlohmann/json.hpp> <cmath> <vector>
                                               <string> <memory> <functional>)
    endif()
  endif()
  target_precompile_headers(${target} REUSE_FROM ${pch})
endfunction()

function(wb_lab lab)
  cmake_parse_arguments(A "TESTS_USE_GLUE" "TEST_UNITS" "DEPS" ${ARGN})
  set_property(GLOBAL APPEND PROPERTY WB_REGISTERED_LABS ${lab})
  set_property(GLOBAL PROPERTY WB_LAB_DEPS_${lab} ${A_DEPS})
  set_property(GLOBAL PROPERTY WB_LAB_TESTS_USE_GLUE_${lab} ${A_TESTS_USE_GLUE})
  set_property(GLOBAL PROPERTY WB_LAB_TEST_UNITS_${lab} ${A_TEST_UNITS})
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

# The sides this build makes each lab for: the student's files (WB_STUDENT), the solution
# (WB_SOLUTIONS, where the tree has solutions/). The native build and the live build
# (cmake/live.cmake) both loop over them.
function(wb_sides out)
  set(sides)
  if(WB_STUDENT)
    list(APPEND sides student)
  endif()
  if(WB_SOLUTIONS AND EXISTS ${CMAKE_SOURCE_DIR}/solutions)
    list(APPEND sides solution)
  endif()
  set(${out} ${sides} PARENT_SCOPE)
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
  wb_use_pch(${target} LAB)
  target_include_directories(${target} PUBLIC ${CMAKE_SOURCE_DIR}/labs/${lab})
  target_link_libraries(${target} PUBLIC wb_headers)
  # A lab's functions call no other lab's: its DEPS are linked by whatever
  # runs their glue (the executable), not by the library, so that a lab's
  # tests build without its DEPS' files.
  wb_lab_deps(${lab} deps)
  foreach(dep IN LISTS deps)
    wb_lab_library(${dep} ${side})
  endforeach()
endfunction()

# A lab and its DEPS, theirs in turn, each once: `lab` first.
function(wb_lab_closure lab out)
  set(result ${lab})
  wb_lab_deps(${lab} deps)
  foreach(dep IN LISTS deps)
    wb_lab_closure(${dep} sub)
    list(APPEND result ${sub})
  endforeach()
  list(REMOVE_DUPLICATES result)
  set(${out} ${result} PARENT_SCOPE)
endfunction()

# What links a lab's glue on one side: every glue library of the closure,
# then every side library (static libraries: the callers before the callees).
function(wb_lab_link_items lab side out)
  wb_lab_closure(${lab} labs)
  set(glues)
  set(libs)
  foreach(l IN LISTS labs)
    wb_lab_glue(${l} g)
    list(APPEND glues ${g})
    list(APPEND libs ${l}_${side})
  endforeach()
  set(${out} ${glues} ${libs} PARENT_SCOPE)
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
    set(prebuilt FALSE)
    if(glue)
      wb_prebuilt_import(${target} prebuilt)
      if(NOT prebuilt)
        add_library(${target} STATIC ${glue})
        wb_prebuilt_part(lib ${target})
      endif()
    else()
      add_library(${target} INTERFACE)
    endif()
    get_target_property(type ${target} TYPE)
    set(scope PUBLIC)
    if(type STREQUAL "INTERFACE_LIBRARY")
      set(scope INTERFACE)
    endif()
    if(prebuilt)
      set(scope INTERFACE)  # an imported target takes its usage requirements only
    endif()
    target_include_directories(${target} ${scope} ${glue_dir} ${CMAKE_SOURCE_DIR}/labs/${lab})
    target_link_libraries(${target} ${scope} wb_run)
    # A glue that needs a library of its own says so in glue.cmake (it sees
    # ${target} and ${scope}), e.g. the implicit lab's CHOLMOD.
    if(EXISTS ${glue_dir}/glue.cmake)
      include(${glue_dir}/glue.cmake)
    endif()
    if(glue AND NOT prebuilt)
      wb_use_pch(${target})
    endif()
    wb_lab_deps(${lab} deps)
    foreach(dep IN LISTS deps)
      wb_lab_glue(${dep} dep_glue)
      target_link_libraries(${target} ${scope} ${dep_glue})
    endforeach()
  endif()
  set(${out} ${target} PARENT_SCOPE)
endfunction()

# The grader's worker of one lab on one side (WB_WORKER_DIR holds tools/grader/cpp/ and the
# files tools/grader/stubs.py generated from the lab's headers): <lab>_client, the stubs the
# tests link, and the executable <lab>[-solution]-worker, the only one with the lab's code.
function(wb_lab_worker lab side suffix)
  set(dir ${WB_WORKER_DIR})
  wb_lab_closure(${lab} labs)
  set(include_dirs ${dir} ${CMAKE_SOURCE_DIR}/tests/${lab}/kernels)
  file(GLOB kernel_sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/${lab}/kernels/*.cpp)
  foreach(l IN LISTS labs)
    list(APPEND include_dirs ${CMAKE_SOURCE_DIR}/labs/${l})
  endforeach()
  if(NOT TARGET wb_rpc_client)
    # Compiled once for every lab: the wire format, the client's runtime, the worker's loop.
    add_library(wb_rpc_client OBJECT ${dir}/client.cpp ${dir}/wb_rpc.cpp)
    add_library(wb_rpc_worker OBJECT ${dir}/worker_main.cpp ${dir}/wb_rpc.cpp)
    foreach(t IN ITEMS wb_rpc_client wb_rpc_worker)
      target_include_directories(${t} PRIVATE ${dir})
      target_link_libraries(${t} PRIVATE wb_headers)
      wb_use_pch(${t} LAB)
    endforeach()
  endif()
  if(NOT TARGET ${lab}_client)
    add_library(${lab}_client STATIC ${dir}/${lab}_client.cpp $<TARGET_OBJECTS:wb_rpc_client>)
    target_include_directories(${lab}_client PRIVATE ${include_dirs})
    target_link_libraries(${lab}_client PUBLIC wb_headers)
    wb_use_pch(${lab}_client LAB)
  endif()
  set(worker ${lab}${suffix}-worker)
  add_executable(${worker} ${dir}/${lab}_worker.cpp ${kernel_sources}
                           $<TARGET_OBJECTS:wb_rpc_worker>)
  target_include_directories(${worker} PRIVATE ${include_dirs})
  target_link_libraries(${worker} PRIVATE ${lab}_${side} wb_headers)
  wb_use_pch(${worker} LAB)
  # tools/adversary only (fuzz/adversary/, never in the grader's scratch copy): a worker that
  # answers every call with values it chooses, no lab code linked.
  if(EXISTS ${dir}/${lab}_adversary.cpp AND NOT TARGET ${lab}-adversary)
    add_executable(${lab}-adversary EXCLUDE_FROM_ALL ${dir}/${lab}_adversary.cpp
                                                     $<TARGET_OBJECTS:wb_rpc_worker>)
    target_include_directories(${lab}-adversary PRIVATE ${include_dirs})
    target_link_libraries(${lab}-adversary PRIVATE wb_headers)
    wb_use_pch(${lab}-adversary LAB)
  endif()
  # tools/adversary --inputs only: the lab's own code, every call's inputs recorded.
  if(EXISTS ${dir}/${lab}_recorder.cpp AND NOT TARGET ${lab}-recorder)
    add_executable(${lab}-recorder EXCLUDE_FROM_ALL ${dir}/${lab}_recorder.cpp ${kernel_sources}
                                                    $<TARGET_OBJECTS:wb_rpc_worker>)
    target_include_directories(${lab}-recorder PRIVATE ${include_dirs})
    target_link_libraries(${lab}-recorder PRIVATE ${lab}_${side} wb_headers)
    wb_use_pch(${lab}-recorder LAB)
  endif()
endfunction()

# The diagnosis probes of one lab (tests/<lab>/probes/*.cpp, tests/common/wb_probe.h): fixed
# inputs on which the grader calls a task's functions to tell mistakes apart. Never built by
# default: <lab>[-solution]-probes links the lab's code in an ordinary build (an instructor's
# look), the worker's stubs in the grader's (tools/diagnosis/probes.py); <lab>-probes-direct,
# with WB_DIRECT_TESTS, links the lab for tools/mutants, which records the catalogue's outputs.
function(wb_lab_probes lab side suffix)
  file(GLOB probe_sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/${lab}/probes/*.cpp)
  if(NOT probe_sources)
    return()
  endif()
  if(NOT TARGET ${lab}_probes_obj)
    # EXCLUDE_FROM_ALL: only the probe executables use these objects, and they are built only
    # when asked for; an ordinary build (a student's first) compiled them for nothing.
    add_library(${lab}_probes_obj OBJECT EXCLUDE_FROM_ALL ${probe_sources}
                                         ${CMAKE_SOURCE_DIR}/tests/common/wb_probe_main.cpp)
    target_include_directories(${lab}_probes_obj PRIVATE ${CMAKE_SOURCE_DIR}/tests/common
                                                         ${CMAKE_SOURCE_DIR}/tests/${lab}/probes
                                                         ${CMAKE_SOURCE_DIR}/labs/${lab})
    wb_lab_deps(${lab} deps)
    foreach(dep IN LISTS deps)
      target_include_directories(${lab}_probes_obj PRIVATE ${CMAKE_SOURCE_DIR}/labs/${dep})
    endforeach()
    target_link_libraries(${lab}_probes_obj PRIVATE wb_headers)
    wb_use_pch(${lab}_probes_obj LAB)
    # One translation unit per lab, as the tests: each file keeps its helpers in a namespace.
    if(WB_UNITY_TESTS)
      set_target_properties(${lab}_probes_obj PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE BATCH
                                                         UNITY_BUILD_BATCH_SIZE 0)
    endif()
  endif()
  set(probes ${lab}${suffix}-probes)
  add_executable(${probes} EXCLUDE_FROM_ALL $<TARGET_OBJECTS:${lab}_probes_obj>)
  if(WB_WORKER_DIR)
    target_link_libraries(${probes} PRIVATE ${lab}_client wb_headers)
    if(WB_DIRECT_TESTS)
      add_executable(${probes}-direct EXCLUDE_FROM_ALL $<TARGET_OBJECTS:${lab}_probes_obj>)
      target_link_libraries(${probes}-direct PRIVATE ${lab}_${side} wb_headers)
    endif()
  else()
    target_link_libraries(${probes} PRIVATE ${lab}_${side} wb_headers)
  endif()
endfunction()

function(wb_add_lab lab side)
  wb_lab_library(${lab} ${side})
  wb_lab_glue(${lab} glue)
  wb_suffix(${side} suffix)
  set(exe ${lab}${suffix})
  # main.cpp compiles once; the side's name comes from a one-line object
  # (framework/src/side.cpp) compiled per side.
  if(NOT TARGET ${lab}_main)
    wb_prebuilt_import(${lab}_main prebuilt)
    if(NOT prebuilt)
      add_library(${lab}_main OBJECT ${CMAKE_SOURCE_DIR}/framework/drivers/${lab}/main.cpp)
      target_link_libraries(${lab}_main PRIVATE ${glue} wb_core)
      target_compile_definitions(${lab}_main PRIVATE WB_LAB="${lab}" WB_SIDE=wb_build_side\(\))
      wb_use_pch(${lab}_main)
      wb_prebuilt_part(obj ${lab}_main)
    endif()
  endif()
  if(NOT TARGET wb_side_${side})
    add_library(wb_side_${side} OBJECT ${CMAKE_SOURCE_DIR}/framework/src/side.cpp)
    target_compile_definitions(wb_side_${side} PRIVATE WB_BUILD_SIDE="${side}")
  endif()
  add_executable(${exe} $<TARGET_OBJECTS:${lab}_main> $<TARGET_OBJECTS:wb_side_${side}>)
  # Glue first, then the side's student functions it calls.
  wb_lab_link_items(${lab} ${side} link_items)
  target_link_libraries(${exe} PRIVATE ${link_items} wb_run wb_core)

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
                                                        ${CMAKE_SOURCE_DIR}/tests/${lab}
                                                        ${CMAKE_SOURCE_DIR}/tests/${lab}/kernels)
    # Not the glue unless asked for (TESTS_USE_GLUE): linking it would make the
    # tests wait for the glue and the run contract to be built.
    get_property(use_glue GLOBAL PROPERTY WB_LAB_TESTS_USE_GLUE_${lab})
    if(use_glue)
      target_link_libraries(${lab}_tests_obj PRIVATE ${glue})
    endif()
    target_link_libraries(${lab}_tests_obj PRIVATE wb_headers Catch2::Catch2)
    wb_use_pch(${lab}_tests_obj TESTS)
    # One translation unit per lab: the test files share Catch's and Eigen's
    # template instantiations instead of compiling them once each (a third of
    # the time). File names and line numbers in failures stay the files' own.
    # Helpers at file scope must therefore have names unique within the lab.
    # TEST_UNITS n in wb_lab() splits a lab whose tests are heavy into n units,
    # so that the grader's 2 jobs share them.
    if(WB_UNITY_TESTS)
      get_property(units GLOBAL PROPERTY WB_LAB_TEST_UNITS_${lab})
      if(units)
        # Named groups, in file order: CMake links BATCH units last-first, which would
        # register (and run) the tests as I4, I5, I1, I2, I3; GROUP units keep their order.
        list(LENGTH test_sources count)
        math(EXPR batch "(${count} + ${units} - 1) / ${units}")
        set(i 0)
        foreach(src IN LISTS test_sources)
          math(EXPR g "${i} / ${batch}")
          if(g LESS 10)
            set(g "0${g}")
          endif()
          set_source_files_properties(${src} PROPERTIES UNITY_GROUP "unit${g}")
          math(EXPR i "${i} + 1")
        endforeach()
        set_target_properties(${lab}_tests_obj PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE GROUP)
      else()
        set_target_properties(${lab}_tests_obj PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE BATCH
                                                          UNITY_BUILD_BATCH_SIZE 0)
      endif()
    endif()
    # The lab's headers (and its dependencies'), without linking a side.
    target_include_directories(${lab}_tests_obj PRIVATE ${CMAKE_SOURCE_DIR}/labs/${lab})
    wb_lab_deps(${lab} deps)
    foreach(dep IN LISTS deps)
      target_include_directories(${lab}_tests_obj PRIVATE ${CMAKE_SOURCE_DIR}/labs/${dep})
    endforeach()
  endif()
  set(tests ${lab}${suffix}-tests)
  # tests/<lab>/kernels/: the loops of long tests as functions (one call instead of millions
  # through the grader's worker); they run beside the lab's code: in the tests here, in the
  # worker in the grader's build.
  file(GLOB kernel_sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/${lab}/kernels/*.cpp)
  if(WB_WORKER_DIR)
    add_executable(${tests} $<TARGET_OBJECTS:${lab}_tests_obj>)
  else()
    add_executable(${tests} $<TARGET_OBJECTS:${lab}_tests_obj> ${kernel_sources})
    target_include_directories(${tests} PRIVATE ${CMAKE_SOURCE_DIR}/tests/${lab}/kernels)
    if(kernel_sources)
      wb_use_pch(${tests} LAB)
    endif()
    target_link_libraries(${tests} PRIVATE ${lab}_${side})
  endif()
  get_property(use_glue GLOBAL PROPERTY WB_LAB_TESTS_USE_GLUE_${lab})
  if(use_glue)
    target_link_libraries(${tests} PRIVATE ${link_items} wb_run)
  endif()
  if(WB_WORKER_DIR)
    # The grader's build (tools/grader/worker.py, docs/grading.md "The worker"): the tests
    # link generated stubs that call the lab's functions in a separate, sandboxed worker
    # process (<lab>[-solution]-worker), so that no student code runs in the test process.
    wb_lab_worker(${lab} ${side} "${suffix}")
    target_link_libraries(${tests} PRIVATE ${lab}_client ${WB_CATCH_MAIN})
    if(WB_DIRECT_TESTS)
      # tools/mutants only: the same tests linked straight with the lab's code, for our own
      # mutants (trusted code), built only when asked for. Never used to grade a submission.
      add_executable(${tests}-direct EXCLUDE_FROM_ALL $<TARGET_OBJECTS:${lab}_tests_obj>
                                                      ${kernel_sources})
      target_include_directories(${tests}-direct PRIVATE ${CMAKE_SOURCE_DIR}/tests/${lab}/kernels)
      if(kernel_sources)
        wb_use_pch(${tests}-direct LAB)
      endif()
      if(use_glue)
        target_link_libraries(${tests}-direct PRIVATE ${link_items} wb_run)
      endif()
      target_link_libraries(${tests}-direct PRIVATE ${lab}_${side} ${WB_CATCH_MAIN})
    endif()
  else()
    target_link_libraries(${tests} PRIVATE ${lab}_${side} ${WB_CATCH_MAIN})
  endif()
  wb_lab_probes(${lab} ${side} "${suffix}")
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
