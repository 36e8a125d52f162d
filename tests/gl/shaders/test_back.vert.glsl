// Test shader (tests/gl/test_gllayer.c): the default fullscreen.vert mirrored in
// x, so the triangle still covers the whole viewport but is back-facing
// (clockwise), for tests of two-sided stencil and culling.
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(1.0 - p.x * 2.0, p.y * 2.0 - 1.0, 0.0, 1.0);
}
