// The visibility renderer's shading pass (Burns and Hunt 2013; derivatives as Schied and
// Dachsbacher 2015): a work group per TILE_SIZE x TILE_SIZE tile (the light grid of
// tile_cull.comp, renderers/tiled/grid.h), an invocation per pixel.
// Each pixel reads its id, rebuilds its triangle from the geometry buffers and shades it
// as forward_tiled.frag would. How (barycentrics, derivatives), MSAA_SAMPLES, what is
// counted and the defines: the comment above main().
#include "bindings.h"
#include "frame.inc"
#include "environment.inc"
#include "lighting.inc"
#include "lights.inc"
#include "tiles.inc"
#include "fog.inc"
#ifdef SKINNING
#include "skin.inc"
#endif
// the edge rule at msaa > 1; its EdgeMaterial is VisSurface's material at any msaa
#define EDGE_RULE_SURFACES_ONLY
#include "edge_rule.inc"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;
#ifdef MSAA_SAMPLES
#define HDR_IMAGE image2DMS
layout(binding = BIND_TEX_VISIBILITY) uniform usampler2DMS t_visibility;
#else
#define HDR_IMAGE image2D
layout(binding = BIND_TEX_VISIBILITY) uniform usampler2D t_visibility;
#endif
#ifdef HDR_RGBA32F
layout(binding = BIND_IMAGE_HDR, rgba32f) writeonly uniform HDR_IMAGE i_hdr;
#else
layout(binding = BIND_IMAGE_HDR, rgba16f) writeonly uniform HDR_IMAGE i_hdr;
#endif
// the frame's counts, summed over its dispatches (x = 0: shadings, 1: samples covered,
// 2: edge pixels, msaa > 1); visibility.c clears them before the first dispatch
layout(binding = BIND_IMAGE_VIS_COUNTS, r32ui) uniform coherent uimage2D i_counts;
layout(binding = BIND_TEX_DIFFUSE) uniform sampler2D t_diffuse;
layout(binding = BIND_TEX_GLOSS) uniform sampler2D t_gloss;
layout(binding = BIND_TEX_NORMAL) uniform sampler2D t_normal;
layout(binding = BIND_TEX_EMISSIVE) uniform sampler2D t_emissive;

layout(location = LOC_RENDERER) uniform int u_light_count;   // lights in b_lights
layout(location = LOC_RENDERER + 1) uniform int u_draw_first;   // this dispatch's draws:
layout(location = LOC_RENDERER + 2) uniform int u_draw_end;     // [first, end)

#include "tile_shade.inc"

// One visible draw (visibility.c's vis_draw, std430, 160 bytes).
struct Draw {
    mat4 model_view;
    vec4 normal_matrix[3];       // mat3 columns; [0].w: the occlusion strength (PBR)
    vec4 diffuse_specular;       // rgb diffuse, a specular
    vec4 emissive_shininess;     // rgb emissive, a shininess
    uvec4 geometry;              // x: first index, y: base vertex, z: the maps on uv set 1
};
layout(std430, binding = BIND_SSBO_VIS_DRAWS) readonly buffer Draws {
    Draw b_draws[];
};
// Every mesh of the scene, concatenated: 12 floats a vertex (mesh_vertex: position,
// normal, tangent, uv), with UV2 (a common define: the scene's materials read maps from a
// second uv set) two more, that set ((0, 0) for a mesh without), with VERTEX_COLOR (the
// scene has coloured meshes: a common define) one more, the RGBA8 colour (white for a
// mesh without), with SKINNING (the scene has skins: a common define) six more, the 4
// joints as 16-bit halves of 2 words (low half first) and the 4 weights (0 for a mesh
// without: no skin); words that are bits read through a second view of the same buffer;
// and 32-bit indices.
#ifdef UV2
const uint VIS_UV2_WORDS = 2u;
#else
const uint VIS_UV2_WORDS = 0u;
#endif
#ifdef VERTEX_COLOR
const uint VIS_COLOR_WORDS = 1u;
#else
const uint VIS_COLOR_WORDS = 0u;
#endif
#ifdef SKINNING
const uint VIS_SKIN_WORDS = 6u;
#else
const uint VIS_SKIN_WORDS = 0u;
#endif
const uint VIS_VERTEX_WORDS = 12u + VIS_UV2_WORDS + VIS_COLOR_WORDS + VIS_SKIN_WORDS;
#if defined(VERTEX_COLOR) || defined(SKINNING)
layout(std430, binding = BIND_SSBO_VIS_VERTICES) readonly buffer VertexWords {
    uint b_vertex_words[];
};
#endif
layout(std430, binding = BIND_SSBO_VIS_VERTICES) readonly buffer Vertices {
    float b_vertices[];
};
layout(std430, binding = BIND_SSBO_VIS_INDICES) readonly buffer Indices {
    uint b_mesh_indices[];
};

const uint VIS_EMPTY = 0xffffffffu;

// surface.inc's safe_normalize (that file declares fragment inputs: not includable here)
vec3 vis_safe_normalize(vec3 n, vec3 fallback)
{
    float len2 = dot(n, n);
    return len2 > 1e-20 ? n * inversesqrt(len2) : fallback;
}

// The perspective-correct barycentrics of NDC point p: m_inv is the inverse of the
// matrix of the clip positions' (x, y, w) columns.
vec3 barycentrics(mat3 m_inv, vec2 p)
{
    vec3 l = m_inv * vec3(p, 1.0);
    return l / (l.x + l.y + l.z);
}

vec3 vertex_attr3(uint v, uint offset)
{
    uint b = v * VIS_VERTEX_WORDS + offset;
    return vec3(b_vertices[b], b_vertices[b + 1u], b_vertices[b + 2u]);
}

#ifdef SKINNING
// Vertex v's skin matrix (skin.inc's, from its joints and weights in the copy).
mat4 vis_skin(uint v)
{
    uint b = v * VIS_VERTEX_WORDS + 12u + VIS_UV2_WORDS + VIS_COLOR_WORDS;
    uint j01 = b_vertex_words[b], j23 = b_vertex_words[b + 1u];
    uvec4 j = uvec4(j01 & 0xffffu, j01 >> 16, j23 & 0xffffu, j23 >> 16);
    vec4 w = vec4(b_vertices[b + 2u], b_vertices[b + 3u], b_vertices[b + 4u],
                  b_vertices[b + 5u]);
    return skin_matrix(j, w);
}
#endif

// Whether id (not empty) is one of this dispatch's draws.
bool in_run(uint id)
{
    uint draw = id >> uint(VIS_TRI_BITS);
    return id != VIS_EMPTY && draw >= uint(u_draw_first) && draw < uint(u_draw_end);
}

// The triangle of id (not empty): its draw, its vertices, their view positions, and the
// inverse of the matrix of its clip positions' (x, y, w) columns.
struct VisTriangle {
    uint draw;
    uint v[3];
    vec3 vpos[3];
    mat3 m_inv;
    bool front;   // counter-clockwise in window coordinates (GL's front face)
#ifdef SKINNING
    mat3 skin3[3];   // the vertices' skin matrices' 3x3, for normals and tangents
#endif
};

VisTriangle vis_triangle(uint id)
{
    VisTriangle t;
    t.draw = id >> uint(VIS_TRI_BITS);
    uint tri = id & ((1u << uint(VIS_TRI_BITS)) - 1u);
    uvec4 geometry = b_draws[t.draw].geometry;
    mat4 model_view = b_draws[t.draw].model_view;
    vec4 clip[3];
    for (uint k = 0u; k < 3u; k++) {
        t.v[k] = geometry.y + b_mesh_indices[geometry.x + 3u * tri + k];
        vec3 position = vertex_attr3(t.v[k], 0u);
#ifdef SKINNING
        mat4 skin = vis_skin(t.v[k]);
        position = (skin * vec4(position, 1.0)).xyz;
        t.skin3[k] = mat3(skin);
#endif
        vec4 p = model_view * vec4(position, 1.0);
        t.vpos[k] = p.xyz;
        clip[k] = f_proj * p;
    }
    mat3 m = mat3(clip[0].xyw, clip[1].xyw, clip[2].xyw);
    t.front = determinant(m) > 0.0;
    t.m_inv = inverse(m);
    return t;
}

// Pixel px's centre in NDC.
vec2 pixel_ndc(ivec2 px)
{
    return (vec2(px) + 0.5) * (2.0 * f_viewport.zw) - 1.0;
}

// Vertex k's normal (skinned, as mesh.vert's).
vec3 vis_vertex_normal(VisTriangle t, uint k)
{
#ifdef SKINNING
    return t.skin3[k] * vertex_attr3(t.v[k], 3u);
#else
    return vertex_attr3(t.v[k], 3u);
#endif
}

// The surface's normal before any normal map, at barycentrics l and position P:
// surface.inc's surface_get from the interpolated vertex normals, facing the side drawn.
vec3 vis_normal(VisTriangle t, mat3 nm, vec3 l, vec3 P)
{
    vec3 N = nm * (l.x * vis_vertex_normal(t, 0u) + l.y * vis_vertex_normal(t, 1u) +
                   l.z * vis_vertex_normal(t, 2u));
    vec3 n = vis_safe_normalize(N, vis_safe_normalize(-P, vec3(0.0, 0.0, 1.0)));
    return t.front ? n : -n;
}

mat3 draw_normal_matrix(uint draw)
{
    vec4 c[3] = b_draws[draw].normal_matrix;
    return mat3(c[0].xyz, c[1].xyz, c[2].xyz);
}

// Surface id (in_run) at pixel px's centre, as surface.inc's surface_get makes it in a
// forward pass: its view position, its normal (maps applied) and its material, which
// the edge rule compares (edge_rule.inc) and shade_surface lights.
struct VisSurface {
    vec3 P, n;
    EdgeMaterial m;
};

VisSurface vis_surface(uint id, ivec2 px)
{
    VisTriangle tr = vis_triangle(id);
    Draw d = b_draws[tr.draw];
    vec4 tan[3];
    vec2 uv[3];
#ifdef UV2
    vec2 uv2[3];
#endif
    for (uint k = 0u; k < 3u; k++) {
        uint b = tr.v[k] * VIS_VERTEX_WORDS;
        tan[k] = vec4(b_vertices[b + 6u], b_vertices[b + 7u], b_vertices[b + 8u],
                      b_vertices[b + 9u]);
#ifdef SKINNING
        tan[k].xyz = tr.skin3[k] * tan[k].xyz;
#endif
        uv[k] = vec2(b_vertices[b + 10u], b_vertices[b + 11u]);
#ifdef UV2
        uv2[k] = vec2(b_vertices[b + 12u], b_vertices[b + 13u]);
#endif
    }
    vec2 step = 2.0 * f_viewport.zw;   // one pixel in NDC
    vec3 l = barycentrics(tr.m_inv, pixel_ndc(px));
    // the derivatives a fragment's 2x2 quad takes (coarse, as texture() gets them): the
    // quad's first pixel against its right and upper neighbours, on this triangle's plane
    vec2 q = pixel_ndc(px & ~1);
    vec3 lq = barycentrics(tr.m_inv, q);
    vec3 lx = barycentrics(tr.m_inv, q + vec2(step.x, 0.0)) - lq;
    vec3 ly = barycentrics(tr.m_inv, q + vec2(0.0, step.y)) - lq;

    vec3 P = l.x * tr.vpos[0] + l.y * tr.vpos[1] + l.z * tr.vpos[2];
    vec2 UV = l.x * uv[0] + l.y * uv[1] + l.z * uv[2];
    vec2 uv_dx = lx.x * uv[0] + lx.y * uv[1] + lx.z * uv[2];
    vec2 uv_dy = ly.x * uv[0] + ly.y * uv[1] + ly.z * uv[2];
#ifdef UV2
    // per map (surface.inc's map_uv): the first set, or the second for the draw's maps
    vec2 UV1 = l.x * uv2[0] + l.y * uv2[1] + l.z * uv2[2];   // set 1 (UV2 is the define)
    vec2 uv1_dx = lx.x * uv2[0] + lx.y * uv2[1] + lx.z * uv2[2];
    vec2 uv1_dy = ly.x * uv2[0] + ly.y * uv2[1] + ly.z * uv2[2];
    uint on1 = d.geometry.z;
#define MAP_UV(bit) ((on1 & (bit)) != 0u ? UV1 : UV), ((on1 & (bit)) != 0u ? uv1_dx : uv_dx), \
                    ((on1 & (bit)) != 0u ? uv1_dy : uv_dy)
#else
#define MAP_UV(bit) UV, uv_dx, uv_dy
#endif

    // surface.inc's surface_get, from the interpolated values
    vec3 n = vis_normal(tr, draw_normal_matrix(tr.draw), l, P);
#ifdef NORMAL_MAP
    vec4 T = l.x * tan[0] + l.y * tan[1] + l.z * tan[2];
    T.xyz = mat3(d.model_view) * T.xyz;
    vec3 t = T.xyz - n * dot(n, T.xyz);
    float tl2 = dot(t, t);
    if (tl2 > 1e-20) {
        t *= inversesqrt(tl2);
        vec3 bt = cross(n, t) * T.w;
        vec3 mn = textureGrad(t_normal, MAP_UV(4u)).xyz * 2.0 - 1.0;
        n = vis_safe_normalize(t * mn.x + bt * mn.y + n * mn.z, n);
    }
#endif
    vec3 diffuse = d.diffuse_specular.rgb;
#ifdef DIFFUSE_MAP
    diffuse *= textureGrad(t_diffuse, MAP_UV(1u)).rgb;
#endif
#ifdef VERTEX_COLOR
    vec3 vc = vec3(0.0);
    for (uint k = 0u; k < 3u; k++)
        vc += l[k] * unpackUnorm4x8(b_vertex_words[tr.v[k] * VIS_VERTEX_WORDS + 12u +
                                                    VIS_UV2_WORDS]).rgb;
    diffuse *= vc;
#endif
    float gloss = d.diffuse_specular.a;
    float shininess = d.emissive_shininess.a;
    float occlusion = 1.0;
#if defined(GLOSS_MAP) && defined(SHADING_PBR)
    vec3 orm = textureGrad(t_gloss, MAP_UV(2u)).rgb;   // surface.inc's ORM map
    occlusion = 1.0 + d.normal_matrix[0].w * (orm.r - 1.0);
    shininess *= orm.g;
    gloss *= orm.b;
#elif defined(GLOSS_MAP)
    gloss *= textureGrad(t_gloss, MAP_UV(2u)).r;
#endif
    vec3 emissive = d.emissive_shininess.rgb;
#ifdef EMISSIVE_MAP
    vec4 e = textureGrad(t_emissive, MAP_UV(8u));   // rgb: colour, a: mask
    emissive *= e.rgb * e.a;
#endif

    return VisSurface(P, n, EdgeMaterial(diffuse, emissive, vec3(0.04), gloss, occlusion,
                                         shininess));
}

// The light of surface s at pixel px.
vec4 shade_surface(VisSurface s, ivec2 px)
{
    vec3 P = s.P, n = s.n;
    vec3 c = ambient_light(P, n, s.m.diffuse, s.m.gloss, s.m.shininess, s.m.occlusion) +
             s.m.emissive;
#ifdef NO_GRID
    uint first = 0u, count = uint(u_light_count);
    uvec2 tile = uvec2(0u);
#else
    uvec2 tile = uvec2(px) / uint(TILE_SIZE);
    uvec4 list = b_tiles[tile.y * uint(TILES_X) + tile.x];
    uint first = list.x, count = list.y;
#endif
    tile_lights_add(c, first, count, tile, P, n, s.m.diffuse, s.m.gloss, s.m.shininess);
    return forward_output(c, P.z, 1.0);
}

vec4 shade_id(uint id, ivec2 px)
{
    return shade_surface(vis_surface(id, px), px);
}

// Each pixel reads its id from the visibility target and, when its draw is in this
// dispatch's range
// [u_draw_first, u_draw_end) (one dispatch per run of visible draws whose materials bind
// the same maps), fetches the triangle's three vertices from the geometry buffers,
// transforms them with the draw's model-view and the frame's projection, and takes the
// perspective-correct barycentrics of the pixel centre in closed form from the clip
// positions (2D homogeneous: with M the columns (x, y, w) of the three clip positions,
// lambda is M^-1 (p, 1) normalised to sum 1; no division by w, so vertices behind the eye
// need no care). Their screen-space derivatives: the same closed form at the right and
// upper neighbours of the first pixel of the pixel's 2x2 quad, minus at that pixel: the
// coarse differences a fragment quad takes of the triangle's plane (its helper
// invocations extrapolate it), so textureGrad gets the uv derivatives texture() gets in
// the forward passes (one-pixel differences at the pixel itself gave 9/255 on a few
// pixels of the agreement test where the mip level changes within a quad; these, 0).
// Position, normal, tangent and uv are interpolated with lambda, the surface is made as
// surface.inc makes it (the same operations, textureGrad for texture), then ambient x
// diffuse + emissive and the tile's lights (tile_shade.inc's tile_lights_add, the loop
// forward_tiled.frag runs), fog (forward_output), stored into the HDR target (image unit
// BIND_IMAGE_HDR).
// MSAA_SAMPLES (msaa > 1): the ids and the HDR target are multisampled. A pixel whose
// samples hold different ids is an edge only by deferred's rule (edge_rule.inc's
// edge_surfaces_differ) on the ids' surfaces rebuilt at the pixel centre; any other
// pixel is shaded once with sample 0's surface, stored into every sample; an edge pixel
// shades each distinct id once, at the pixel centre as a forward pass shades every
// triangle that covers a sample, stored into the samples holding it. TILE_DEPTH_RANGES
// (with it, when lights are culled): a centre outside the depth range its tile was
// culled against loops every light, as forward_tiled.frag does.
// Counted (i_counts, an image atomic per shading pixel and counter): the shadings (the
// pass's samples_shaded), the samples covered (its samples) and, msaa > 1, the edge
// pixels (edge_fraction). Not reduced per work group first: the barrier that needs cost
// llvmpipe 15-20 % of the pass (compare --exe, 5 paired rounds, 640x360 curtis-scene3).
// Defines: TILE_SIZE, TILES_X, VIS_TRI_BITS, NO_GRID (no point or spot light: every
// light of the frame looped), the material's map defines (DIFFUSE_MAP, GLOSS_MAP,
// NORMAL_MAP, EMISSIVE_MAP), FOG, SHADOWS, HDR_RGBA32F, MSAA_SAMPLES, TILE_DEPTH_RANGES;
// the common ones, VERTEX_COLOR, UV2 and SKINNING (each vertex skinned as mesh.vert
// skins it, skin.inc, before the draw's model-view: the same position the visibility
// pass rasterised).
void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= int(f_viewport.x) || px.y >= int(f_viewport.y))
        return;
    uint shaded = 0u, covered = 0u;
#ifdef MSAA_SAMPLES
    uint ids[MSAA_SAMPLES];
    bool mixed = false;   // samples of more than one id (or of an id and of nothing)
    for (int k = 0; k < MSAA_SAMPLES; k++) {
        ids[k] = texelFetch(t_visibility, px, k).r;
        mixed = mixed || ids[k] != ids[0];
    }
    // deferred's edge rule (edge_rule.inc) on the surfaces of the pixel's ids at its
    // centre: two triangles of one smooth surface and one material are no edge. Two
    // draws are: a surface's material is read with its draw's maps, which only the
    // dispatch of its draw binds, and each dispatch must classify the pixel alike
    bool edge = false;
    bool own = in_run(ids[0]);
    VisSurface s0;
    if (own)
        s0 = vis_surface(ids[0], px);
    for (int k = 1; k < MSAA_SAMPLES && mixed && !edge; k++) {
        if (ids[k] == ids[0])
            continue;
        if (ids[0] == VIS_EMPTY || ids[k] == VIS_EMPTY ||
            (ids[k] >> uint(VIS_TRI_BITS)) != (ids[0] >> uint(VIS_TRI_BITS))) {
            edge = true;
        } else if (own) {   // one draw: only its dispatch writes the pixel
            VisSurface s = vis_surface(ids[k], px);
            edge = edge_surfaces_differ(true, s0.P, s0.n, true, s.P, s.n) ||
                   edge_materials_differ(s0.m, s.m);
        }
    }
    if (!edge && own) {
        // sample 0's surface for every sample: shaded once
        shaded = 1u;
        covered = uint(MSAA_SAMPLES);
        vec4 c = shade_surface(s0, px);
        for (int j = 0; j < MSAA_SAMPLES; j++)
            imageStore(i_hdr, px, j, c);
    }
    // an edge: each distinct id shaded once at the pixel centre (what a forward pass
    // shades for each triangle covering some sample) and stored into the samples that
    // hold it
    for (int k = 0; k < MSAA_SAMPLES && edge; k++) {
        if (!in_run(ids[k]))
            continue;
        covered++;
        bool done = false;
        for (int j = 0; j < k; j++)
            done = done || ids[j] == ids[k];
        if (done)
            continue;
        shaded++;
        vec4 c = shade_id(ids[k], px);
        for (int j = k; j < MSAA_SAMPLES; j++)
            if (ids[j] == ids[k])
                imageStore(i_hdr, px, j, c);
    }
    // a pixel's ids are read by every dispatch: its edge counted once, by the dispatch
    // of sample 0's draw (the first when sample 0 has none)
    if (edge && (ids[0] == VIS_EMPTY ? u_draw_first == 0 : own))
        imageAtomicAdd(i_counts, ivec2(2, 0), 1u);
#else
    uint id = texelFetch(t_visibility, px, 0).r;
    if (in_run(id)) {
        shaded = covered = 1u;
        imageStore(i_hdr, px, shade_id(id, px));
    }
#endif
    if (shaded > 0u) {
        imageAtomicAdd(i_counts, ivec2(0, 0), shaded);
        imageAtomicAdd(i_counts, ivec2(1, 0), covered);
    }
}
