// Test shader (tests/gl/test_feedback.c): one invocation copies texel (0, 0) of the
// texture at unit 0 into a storage buffer, so that a dispatch samples a texture.
layout(local_size_x = 1) in;
layout(binding = 0) uniform sampler2D t_input;
layout(std430, binding = 0) buffer Out { vec4 v_out; };

void main()
{
    v_out = texelFetch(t_input, ivec2(0), 0);
}
