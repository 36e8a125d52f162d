// `shadesweep probe`'s full-screen read: each fragment of a target a quarter of the
// texture's width and height sums the 4x4 texels of its block (every texel read once).
layout(binding = 0) uniform sampler2D t_src;
layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * 4;
    vec4 s = vec4(0.0);
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++)
            s += texelFetch(t_src, base + ivec2(x, y), 0);
    o_color = s;
}
