// Test shader (tests/gl/test_gllayer.c): writes u_color, or with FRAGCOORD the
// pixel's own coordinates (x/255, y/255, u_color.b, u_color.a), or with READ_UV
// fullscreen.vert's v_uv (v_uv, u_color.b, u_color.a), to every colour output.
// SAMPLE adds texel (0, 0) of the texture at unit 0 (tests/gl/test_feedback.c).
// OUTPUTS (default 1) is the number of colour outputs, for MRT tests.
// TEST_EARLY_ERROR, TEST_COMPILE_ERROR, TEST_INCLUDE_ERROR (in test_common.inc)
// and TEST_LINK_ERROR break the shader on purpose.
#ifdef TEST_EARLY_ERROR
this_line_comes_before_any_include;   // the test checks this line number
#endif
#include "test_common.inc"

#ifndef OUTPUTS
#define OUTPUTS 1
#endif

layout(location = 0) out vec4 o_color[OUTPUTS];
layout(location = 0) uniform vec4 u_color;

#ifdef READ_UV
layout(location = 0) in vec2 v_uv;   // as fullscreen.vert writes it
#endif
#ifdef TEST_LINK_ERROR
in vec4 v_not_written_by_any_vertex_shader;
#endif
#ifdef SAMPLE
layout(binding = 0) uniform sampler2D t_input;
#endif

void main()
{
    vec4 c = u_color;
#ifdef FRAGCOORD
    c.xy = test_pixel_coord();
#endif
#ifdef READ_UV
    c.xy = v_uv;
#endif
#ifdef TEST_LINK_ERROR
    c += v_not_written_by_any_vertex_shader;
#endif
#ifdef SAMPLE
    c += texelFetch(t_input, ivec2(0), 0);
#endif
#ifdef TEST_COMPILE_ERROR
    c = this_is_not_declared;   // the test checks this line number
#endif
    for (int i = 0; i < OUTPUTS; i++)
        o_color[i] = c;
}
