// The full-screen triangle: 3 vertices, no vertex attributes (the state cache's
// empty vertex array). Draw it with gl_state_draw_fullscreen() (state.h), which
// sets the viewport this shader expects and binds the empty vertex array.
//
// Either way the triangle's corners land on the target's pixels (0,0), (2W,0) and
// (0,2H): it holds the whole W x H target, every pixel centre is covered exactly
// once, and v_uv runs 0..1 across the target (0,0 at the bottom left).
// (The default, FULLSCREEN_UNCLIPPED and FULLSCREEN_FAR: the comment above main().)
layout(location = 0) out vec2 v_uv;   // fragment shaders: layout(location = 0) in vec2 v_uv;

// - Default: viewport (0,0,W,H), corners at clip (-1,-1), (3,-1), (-1,3). GL clips
//   the triangle to the viewport. Mesa's llvmpipe splits the clipped polygon into
//   two triangles, and counts fragment shader invocations per 4x4 block per
//   triangle, so the blocks on the split's diagonal count twice (64x48 reports
//   3456 invocations, not 3072).
// - FULLSCREEN_UNCLIPPED: viewport (0,0,2W,2H), corners at clip (-1,-1), (1,-1),
//   (-1,1): inside the clip volume, so nothing is clipped or split, and
//   GL_FRAGMENT_SHADER_INVOCATIONS is exactly W*H on llvmpipe too. Needs a
//   viewport of 2W x 2H within GL_MAX_VIEWPORT_DIMS.
// - FULLSCREEN_FAR: z = w, so the triangle lies on the far plane (depth 1): drawn with
//   depth test LEQUAL against a depth buffer cleared to 1 it covers only the pixels no
//   geometry wrote, and early depth testing skips the others (the sky).
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));   // (0,0) (2,0) (0,2)
    v_uv = p;
#ifdef FULLSCREEN_FAR
    const float z = 1.0;
#else
    const float z = 0.0;
#endif
#ifdef FULLSCREEN_UNCLIPPED
    gl_Position = vec4(p - 1.0, z, 1.0);
#else
    gl_Position = vec4(p * 2.0 - 1.0, z, 1.0);
#endif
}
