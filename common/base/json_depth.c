#include "base/json_depth.h"

#include <stdio.h>

int json_depth_check(const char *text, size_t n, char *err, size_t errlen)
{
    int depth = 0, in_string = 0;
    for (size_t i = 0; i < n; i++) {
        char c = text[i];
        if (in_string) {
            if (c == '\\')
                i++; /* the escaped character, a quote included */
            else if (c == '"')
                in_string = 0;
        } else if (c == '"') {
            in_string = 1;
        } else if (c == '[' || c == '{') {
            if (++depth > JSON_DEPTH_MAX) {
                snprintf(err, errlen, "JSON nested deeper than %d levels (at byte %zu)",
                         JSON_DEPTH_MAX, i);
                return -1;
            }
        } else if ((c == ']' || c == '}') && depth > 0) {
            depth--;
        }
    }
    return 0;
}
