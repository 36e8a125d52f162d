// `shadesweep probe`'s fill rate (renderers/probe/probe.c): the cheapest fragment that
// writes its target. UINT_OUT: an unsigned-integer target (R32UI).
layout(location = 0) in vec2 v_uv;
#ifdef UINT_OUT
layout(location = 0) out uvec4 o_color;
#else
layout(location = 0) out vec4 o_color;
#endif

void main()
{
#ifdef UINT_OUT
    o_color = uvec4(uint(gl_FragCoord.x) ^ uint(gl_FragCoord.y));
#else
    o_color = vec4(v_uv, 0.25, 0.5);
#endif
}
