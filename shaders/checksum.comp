// A buffer range's checksum on the GPU (node/gpu_checksum.c): word i of the range adds
// mix(w ^ mix(i + salt)) to one 32-bit sum and a second mix of that to another. Wrapping
// addition is order free, so the parallel sum gives every node the same bits; mix is a
// bijection, so one changed word always changes the first sum.
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Data { uint words[]; };
layout(std430, binding = 1) coherent buffer Sum { uint sums[]; };
uniform int u_offset, u_count, u_salt, u_slot;
uniform int u_width, u_stride; // word i is word i % u_width of record i / u_width
shared uvec2 part[256];

uint mix32(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

void main()
{
    uint i = gl_GlobalInvocationID.x, l = gl_LocalInvocationIndex;
    uvec2 v = uvec2(0u);
    if (i < uint(u_count)) {
        uint at = uint(u_offset) + (i / uint(u_width)) * uint(u_stride) + i % uint(u_width);
        uint a = mix32(words[at] ^ mix32(i + uint(u_salt) * 0x9e3779b9u));
        v = uvec2(a, mix32(a ^ 0x85ebca6bu));
    }
    part[l] = v;
    barrier();
    for (uint s = 128u; s > 0u; s >>= 1) {
        if (l < s)
            part[l] += part[l + s];
        barrier();
    }
    if (l == 0u) {
        atomicAdd(sums[2 * u_slot], part[0].x);
        atomicAdd(sums[2 * u_slot + 1], part[0].y);
    }
}
