// Hostile: replaces the tests' helpers and operator new (plain C++, nothing denied by name).
#include <cstddef>
#include <cstdlib>
#include <string>

#include "explicit_euler.h"

namespace wbtest {
bool near(double, double, double, double) { return true; }
void require_near(const wb::Vec2&, const wb::Vec2&, double, const std::string&, double) {}
void require_near(double, double, double, const std::string&, double) {}
}  // namespace wbtest

void* operator new(std::size_t n) { return std::malloc(n ? n : 1); }
void operator delete(void* p) noexcept { std::free(p); }

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
}
