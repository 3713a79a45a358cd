/* libFuzzer entry point of the design harness (fuzz/harness.c); built by `make fuzz`. */
#include "harness.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return rg2f_design(data, size); }
