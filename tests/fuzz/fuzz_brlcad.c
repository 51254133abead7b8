/* tests/fuzz/fuzz_brlcad.c -- libFuzzer target for the BRL-CAD reader (`make fuzz`), seeded with the sample
 * databases. A crash, a sanitizer report, a refusal without a message or a scene that breaks its invariants
 * aborts; save the input into tests/data/fuzz-brlcad/ and tests/t_brlcad_errors.c replays it in every
 * `make test`. */
#include "../brlcad_exercise.h"
#include <stdint.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (brlcad_exercise((const char *)data, size) < 0)
        abort();
    return 0;
}
