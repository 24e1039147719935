// Deterministic float32 summation: each invocation accumulates its share with
// Kahan compensation, then the workgroup adds the 256 results as a fixed binary
// tree in shared memory. No atomics, so every run gives the same bits; error
// grows with log2(n), not n, which keeps 4096x4096 sums within 1e-6 relative.
const uint WG = 256u;
shared vec4 partial_sums[WG];

void kahan_add(inout vec4 sum, inout vec4 comp, vec4 v) {
    precise vec4 y = v - comp;
    precise vec4 t = sum + y;
    comp = (t - sum) - y;
    sum = t;
}

// Returns the workgroup total in invocation 0 (undefined elsewhere).
vec4 workgroup_sum(vec4 sum, vec4 comp) {
    uint tid = gl_LocalInvocationIndex;
    partial_sums[tid] = sum - comp;
    barrier();
    for (uint stride = WG / 2u; stride > 0u; stride >>= 1u) {
        if (tid < stride) partial_sums[tid] = partial_sums[tid] + partial_sums[tid + stride];
        barrier();
    }
    return partial_sums[0];
}
