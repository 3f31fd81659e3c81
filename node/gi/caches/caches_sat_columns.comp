// Summed-area tables, step 1 (val_sat_build()): each column's inclusive sums down its rows.
layout(local_size_x = 64) in;

layout(std430, binding = 4) buffer Sums { vec2 sums[]; };

uniform int u_columns, u_rows;

void main()
{
    int c = int(gl_GlobalInvocationID.x);
    if (c >= u_columns)
        return;
    vec2 s = vec2(0.0);
    for (int y = 0; y < u_rows; y++) {
        s += sums[c * u_rows + y];
        sums[c * u_rows + y] = s;
    }
}
