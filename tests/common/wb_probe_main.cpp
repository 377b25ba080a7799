// The main of every lab's probe binary (<lab>-probes): tests/common/wb_probe.h.
#include "wb_probe.h"

int main(int argc, char** argv) { return wbprobe::main(argc, argv); }
