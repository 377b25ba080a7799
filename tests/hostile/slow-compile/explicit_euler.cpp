#include "explicit_euler.h"
namespace {
// Each constant costs the compiler its whole constexpr budget (seconds) before it
// gives up; 40 of them take minutes.
template <int K>
constexpr long slow() {
  long s = K;
  for (long i = 0; i < 200000; ++i)
    for (long j = 0; j < 200000; ++j) s += (i ^ j) & 1;
  return s;
}
constexpr long k0 = slow<0>();
constexpr long k1 = slow<1>();
constexpr long k2 = slow<2>();
constexpr long k3 = slow<3>();
constexpr long k4 = slow<4>();
constexpr long k5 = slow<5>();
constexpr long k6 = slow<6>();
constexpr long k7 = slow<7>();
constexpr long k8 = slow<8>();
constexpr long k9 = slow<9>();
constexpr long k10 = slow<10>();
constexpr long k11 = slow<11>();
constexpr long k12 = slow<12>();
constexpr long k13 = slow<13>();
constexpr long k14 = slow<14>();
constexpr long k15 = slow<15>();
constexpr long k16 = slow<16>();
constexpr long k17 = slow<17>();
constexpr long k18 = slow<18>();
constexpr long k19 = slow<19>();
constexpr long k20 = slow<20>();
constexpr long k21 = slow<21>();
constexpr long k22 = slow<22>();
constexpr long k23 = slow<23>();
constexpr long k24 = slow<24>();
constexpr long k25 = slow<25>();
constexpr long k26 = slow<26>();
constexpr long k27 = slow<27>();
constexpr long k28 = slow<28>();
constexpr long k29 = slow<29>();
constexpr long k30 = slow<30>();
constexpr long k31 = slow<31>();
constexpr long k32 = slow<32>();
constexpr long k33 = slow<33>();
constexpr long k34 = slow<34>();
constexpr long k35 = slow<35>();
constexpr long k36 = slow<36>();
constexpr long k37 = slow<37>();
constexpr long k38 = slow<38>();
constexpr long k39 = slow<39>();
}  // namespace
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  x(0, 0) += double(k0 + k1 + k2 + k3 + k4 + k5 + k6 + k7 + k8 + k9 + k10 + k11 + k12 + k13 +
                    k14 + k15 + k16 + k17 + k18 + k19 + k20 + k21 + k22 + k23 + k24 + k25 + k26 +
                    k27 + k28 + k29 + k30 + k31 + k32 + k33 + k34 + k35 + k36 + k37 + k38 + k39) *
             0.0;
}
