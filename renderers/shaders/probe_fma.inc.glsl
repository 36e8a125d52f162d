// `shadesweep probe`'s arithmetic rate: n iterations of 4 dependent vec4 FMAs (32 flops
// an iteration), n a uniform so that the compiler cannot fold the loop.
vec4 probe_fma(vec4 a, int n)
{
    const vec4 b = vec4(0.9999, 0.9998, 0.9997, 0.9996), c = vec4(1e-4);
    for (int i = 0; i < n; i++) {
        a = fma(a, b, c);
        a = fma(a, b, c);
        a = fma(a, b, c);
        a = fma(a, b, c);
    }
    return a;
}
