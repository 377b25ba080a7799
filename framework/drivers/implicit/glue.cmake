# The implicit glue's provided solver uses CHOLMOD when the build found it
# (cmake/cholmod.cmake; wb_cholmod is empty otherwise).
target_link_libraries(${target} ${scope} wb_cholmod)
