// Selection (val_sat_select()): slot i takes the texel whose interval of the mixed sums
// holds T (i + u_i) / n, by binary search over the column totals, then down the column;
// it becomes VAL u_first + i with its flux times its weight 1 / (n p) (its area stays its
// texel's: equation 14 of the paper, unbiased).
layout(local_size_x = 64) in;

struct pick {
    int column, row;
    float weight, unused;
};
layout(std430, binding = 2) writeonly buffer Vals { vec4 vals[]; };   // 3 per VAL
layout(std430, binding = 3) writeonly buffer Picks { pick picks[]; };
layout(std430, binding = 4) readonly buffer Sums { vec2 sums[]; };
layout(std430, binding = 5) readonly buffer Row { vec2 row[]; };

uniform int u_slots, u_columns, u_rows, u_first;
uniform int u_seed;

float mix2(vec2 s, float a, float b) { return a * s.x + b * s.y; }

// The first of n entries from base (in sums, or in row when base < 0) whose mixed sum
// exceeds t, or the last; then back to one with a non-empty interval.
int search(int base, int n, float a, float b, float t, out float width)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (mix2(base < 0 ? row[mid] : sums[base + mid], a, b) > t)
            hi = mid;
        else
            lo = mid + 1;
    }
    for (;; lo--) {
        float below = lo > 0 ? mix2(base < 0 ? row[lo - 1] : sums[base + lo - 1], a, b) : 0.0;
        width = mix2(base < 0 ? row[lo] : sums[base + lo], a, b) - below;
        if (width > 0.0 || lo == 0)
            return lo;
    }
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_slots)
        return;
    vec2 last = row[u_columns - 1];
    float weight = 0.0;
    int c = 0, y = 0;
    if (last.y > 0.0) {
        float a = last.x > 0.0 ? 0.5 / last.x : 0.0, b = 0.5 / last.y;
        float total = mix2(last, a, b), column_width, width;
        float target = total * ((float(i) + val_slot_random(uint(u_seed), i)) / float(u_slots));
        c = search(-1, u_columns, a, b, target, column_width);
        float base = c > 0 ? mix2(row[c - 1], a, b) : 0.0;
        y = search(c * u_rows, u_rows, a, b, target - base, width);
        weight = width > 0.0 ? total / (float(u_slots) * width) : 0.0;
    }
    picks[i] = pick(c, y, weight, 0.0);
    val v = val_fetch(ivec3(c % u_rsm_size, y, c / u_rsm_size));
    int o = 3 * (u_first + i);
    vals[o] = vec4(v.position, v.area);
    vals[o + 1] = vec4(v.normal, 0.0);
    vals[o + 2] = vec4(v.flux * weight, 0.0);
}
