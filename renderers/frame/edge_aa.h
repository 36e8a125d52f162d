#pragma once
/* Edge-detect anti-aliasing (the manifest's `aa: edge`): seed 001 section 19.5.2's
 * resolution-independent edge detection, as a post pass on the float HDR image that
 * every renderer that draws adds after its lighting (and sky), before the resolve.
 * The test and the blur, where the normals come from, and what the pass reads and
 * writes: the comment above EDGE_AA_MAX_GBUFFER below. */
#include <stdbool.h>
#include <stddef.h>

#include "renderers/gl/loader.h"
#include "renderers/gl/target.h"
#include "renderers/renderer.h"

/* The pass's state (edge_aa: its target, framebuffers, program) lives in the base
 * (renderers/frame/base.h), which releases it and hands its target to the resolve. */
#include "renderers/frame/base.h"

/* The test (edge_aa.frag.glsl), per pixel, over its 8 neighbours taken as 4 opposite
 * pairs (left/right, top/bottom and the two diagonals), as 19.5.2 describes it:
 *   depth   the two steps of depth from the centre to either neighbour of a pair: the
 *           pair is an edge when the larger is at least 25 x the smaller (19.5.2's
 *           constant), the smaller floored first so that it is never 0. Comparing
 *           the two steps with each other, not with a fixed value, is what makes it
 *           independent of the resolution. Depth is the depth buffer's own window
 *           depth (depth24), in which a plane's depth is linear across the screen,
 *           so both steps are equal on any plane; the floor is 4 of its 2^24 steps
 *           (19.5.2's 0.00001 is for its own depth storage, which it says the
 *           constant depends on).
 *   normal  the cosines between the centre's normal and each neighbour's of the pair:
 *           an edge when they differ by 0.4 or more (19.5.2's constant).
 *   weight  the pairs that are an edge by either test, / 4: 0, 0.25, ... 1.
 * The blur (19.5.2): four bilinear samples at the pixel's centre moved towards its
 * four corners by the weight (at the centre for 0, at the corners for 1), averaged:
 * the pixel blended with its 8 neighbours, the more the more of an edge it is. It is
 * computed as that average's exact weights on the 3 x 3 texels (f = weight / 2:
 * centre (1 - f)^2, each side neighbour f (1 - f) / 2, each corner f^2 / 4), so it
 * needs no filtering state; at the image's border the nearest texel stands in.
 *
 * Normals: deferred renderers (deferred, tiled-deferred, clustered deferred shading)
 * read the G-buffer's (gbuffer.inc, the layout's defines: any preset, normal maps
 * included, as 19.5.2 reads its MRTs); the forward renderers keep no normals, so the
 * pass rebuilds each one from the depth buffer: the view positions of the pixel and
 * its neighbours (unprojected as gbuffer.inc does), the cross product of the smaller
 * of the two one-sided steps along x and along y (so that a step across an edge is
 * not taken). These are the faces' geometric normals, without normal maps or smooth
 * shading normals: the normal test then finds creases alone, and the depth test,
 * the same in both, finds silhouettes.
 *
 * What it reads: the base's hdr (unit BIND_TEX_HDR) and depth (BIND_TEX_DEPTH)
 * targets, and the G-buffer textures the caller names; what it writes: its own
 * target "hdr.aa" (the HDR format, the output's size), which the resolve and
 * read_hdr then take (renderer_base_display). With aa: none nothing is made or run,
 * and the plan lists the pass as skipped. One draw (full screen) a frame, pass
 * "edge-aa". It reads single-sample textures: with multisampled targets (msaa > 1) the
 * resolved HDR image (msaa-resolve first) and depth1, a blit of the multisampled depth
 * to one sample a pixel, with normals rebuilt from it; "hdr.aa" is single-sampled. */
enum { EDGE_AA_MAX_GBUFFER = 6 };

/* At prepare, after renderer_base_targets: with opts.aa == AA_EDGE, the target, its
 * framebuffer and the program (fullscreen.vert + edge_aa.frag), normals from the
 * G-buffer when gbuffer_defines is not NULL (the layout's defines, n of them: what
 * gbuffer.inc needs), else from depth. With aa: none, nothing. False with a message;
 * a second call releases what the first made first. */
bool edge_aa_prepare(renderer_base *b, const char *const *gbuffer_defines, int n,
                     char *err, size_t errlen);
/* The "edge-aa" pass when it runs (nothing otherwise): hdr and depth, and the
 * G-buffer textures gbuffer[0..n) at units BIND_TEX_GBUFFER0 + k (the deferred
 * renderers; NULL, 0 for the forward ones), into "hdr.aa". One draw. */
void edge_aa_pass(renderer_base *b, frame_stats *out, const GLuint *gbuffer, int n);
/* The plan's "edge-aa" row: runs (and where its normals come from) or skipped, why. */
void edge_aa_describe_pass(const renderer_base *b, pass_plan *out);
/* Appends "hdr.aa" to out->target (and target_bytes) when it was made. */
void edge_aa_describe_target(const renderer_base *b, pass_plan *out);
