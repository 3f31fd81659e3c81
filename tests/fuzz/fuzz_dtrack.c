/* libFuzzer target: any bytes through the DTrack parser and into a source state. Built
 * with clang -fsanitize=fuzzer,address,undefined by CMake when clang is present. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "input/input_dtrack.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static input_dtrack_frame f;
    static input_source_state st;
    int bad = input_dtrack_parse((const char *)data, size, &f);
    if (bad != f.lines_bad || f.body_count > INPUT_DTRACK_MAX_BODIES ||
        f.flystick_count > INPUT_DTRACK_MAX_FLYSTICKS || f.marker_count > INPUT_DTRACK_MAX_MARKERS)
        abort();
    for (int i = 0; i < f.body_count; i++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(f.bodies[i].position[k]))
                abort();
    input_dtrack_desc desc = {.head_id = 0, .wand_id = 0};
    input_dtrack_apply(&desc, &f, &st, 1.0);
    for (int i = 0; i < INPUT_AXIS_COUNT; i++)
        if (!(st.axes[i] >= -1.0f && st.axes[i] <= 1.0f))
            abort();
    return 0;
}
