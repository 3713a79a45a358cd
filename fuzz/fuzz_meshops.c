/* libFuzzer entry point of the mesh operations harness (fuzz/harness.c); built by `make fuzz`. */
#include "harness.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return rg2f_meshops(data, size); }
