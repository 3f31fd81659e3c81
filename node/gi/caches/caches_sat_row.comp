// Summed-area tables, step 2 (val_sat_build()): the inclusive sums of the column totals,
// CHUNKS chunks summed in order, then each chunk's offset, in one work group.
#define CHUNKS 256
layout(local_size_x = CHUNKS) in;

layout(std430, binding = 4) readonly buffer Sums { vec2 sums[]; };
layout(std430, binding = 5) buffer Row { vec2 row[]; };

uniform int u_columns, u_rows;

shared vec2 chunk[CHUNKS];

void main()
{
    int k = int(gl_LocalInvocationID.x), per = (u_columns + CHUNKS - 1) / CHUNKS;
    int first = k * per, end = min(first + per, u_columns);
    vec2 s = vec2(0.0);
    for (int c = first; c < end; c++) {
        s += sums[c * u_rows + u_rows - 1];
        row[c] = s;
    }
    chunk[k] = s;
    barrier();
    if (k == 0) { // exclusive offsets, in order
        vec2 offset = vec2(0.0);
        for (int j = 0; j < CHUNKS; j++) {
            vec2 t = chunk[j];
            chunk[j] = offset;
            offset += t;
        }
    }
    barrier();
    for (int c = first; c < end; c++)
        row[c] += chunk[k];
}
