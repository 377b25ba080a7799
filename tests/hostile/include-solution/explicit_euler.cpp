#include "explicit_euler.h"
#include "../../../../solutions/euler/explicit_euler.cpp"
