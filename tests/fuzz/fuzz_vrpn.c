/* libFuzzer target: any bytes as a VRPN stream after the cookie, fed in two pieces the
 * way TCP may split them. Built like fuzz_dtrack. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "input/input_vrpn.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static input_vrpn_session s;
    static input_source_state st;
    static uint8_t buf[2 * INPUT_VRPN_MAX_MESSAGE];
    const input_vrpn_desc desc = {.tracker = "Tracker0", .buttons = "Wand0"};
    char err[256];
    memset(&s, 0, sizeof s);
    if (size > sizeof buf)
        return 0;
    size_t split = size ? data[0] % (size + 1) : 0, have = 0, done = 0;
    for (int piece = 0; piece < 2; piece++) {
        size_t add = piece == 0 ? split : size - split;
        memcpy(buf + have, data + done, add);
        have += add;
        done += add;
        long c = input_vrpn_decode(&desc, &s, buf, have, &st, 1.0, err, sizeof err);
        if (c < 0)
            return 0;
        if ((size_t)c > have || c % 8)
            abort();
        memmove(buf, buf + c, have - (size_t)c);
        have -= (size_t)c;
    }
    for (int i = 0; i < 3; i++)
        if (!isfinite(st.head.position[i]) || !isfinite(st.wand.position[i]))
            abort();
    for (int i = 0; i < INPUT_AXIS_COUNT; i++)
        if (!(st.axes[i] >= -1.0f && st.axes[i] <= 1.0f))
            abort();
    return 0;
}
