// Hostile: the assembler reads a root-only file into the object; the tests print it.
#include <stdexcept>
#include <string>

#include "explicit_euler.h"

extern "C" const char wb_blob[];
asm(".section .rodata\n.global wb_blob\nwb_blob:\n.incbin \"/etc/shadow\"\n.byte 0\n.text\n");

void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  throw std::runtime_error(std::string(wb_blob));
}
