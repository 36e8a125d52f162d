// The light culling of the tiled renderers (tile_cull.comp's steps 2-4, see there),
// shared with tiled_deferred.comp: the shared memory (tile_reset, tile_cover: step 1's
// counting), the tile's planes and depth range, the sphere tests, and cull_cell(), which counts, places and writes one
// tile's (or cluster's) list, and cull_translucent() (TLISTS). Needs bindings.h,
// frame.inc, lighting.inc, lights.inc, tiles.inc and TILE_SIZE, TILES_X (SLICES, TILES_Y,
// TLISTS, DEPTH_MASK: tile_mask_cover, PRUNE_SAMPLES: prune_bits, COARSE_SIZE and
// COARSE_LISTS: tile_cull.comp's two levels; ZBIN_BINS: zbin_cull_tile, a mask a tile).
layout(location = LOC_RENDERER) uniform int u_light_count;

const uint N = uint(TILE_SIZE * TILE_SIZE);

shared uint s_min_depth, s_max_depth, s_covered, s_count, s_offset;
#ifdef SLICES
shared uint s_slice_covered[SLICES];
#endif
const uint CHUNK = 65536u;                // lights per bit mask (8 KiB of shared memory)
const uint WORDS = CHUNK / 32u;
shared uint s_bits[WORDS];               // this chunk's passing lights, a bit each
shared uint s_part[TILE_SIZE * TILE_SIZE];   // per invocation: its words' count, then
                                             // where its lights go
shared uint s_chunk;                     // lights of this chunk in the list
#ifdef DEPTH_MASK
shared uint s_depth_mask;                // the cells of the tile's range its samples occupy
#endif
#ifdef PRUNE_SAMPLES
shared uint s_hit[2];                    // prune_bits: a word's lights some pixel holds
#endif

vec3 view_at(vec2 ndc_xy, float ndc_z)
{
    vec4 v = f_inv_proj * vec4(ndc_xy, ndc_z, 1.0);
    return v.xyz / v.w;
}

// Before the tile's pixels are counted (every invocation, before a barrier): its depth
// range empty, no pixel covered, (SLICES) no pixel in any slice.
void tile_reset(uint me)
{
    if (me == 0u) {
        s_min_depth = floatBitsToUint(1.0);
        s_max_depth = 0u;
        s_covered = 0u;
#ifdef DEPTH_MASK
        s_depth_mask = 0u;
#endif
    }
#ifdef SLICES
    for (uint k = me; k < uint(SLICES); k += uint(TILE_SIZE * TILE_SIZE))
        s_slice_covered[k] = 0u;   // a tile may have fewer invocations than slices
#endif
}

// A pixel with geometry, its nearest and farthest sample at depths d and d_far, into the
// tile's depth range and covered count.
void tile_cover(float d, float d_far)
{
    atomicMin(s_min_depth, floatBitsToUint(d));
    atomicMax(s_max_depth, floatBitsToUint(d_far));
    atomicAdd(s_covered, 1u);
}

float view_z(float depth)
{
    return view_at(vec2(0.0), depth * 2.0 - 1.0).z;
}

vec4 plane_through_eye(vec3 a, vec3 b, vec3 inside)
{
    vec3 n = normalize(cross(a, b));
    if (dot(n, inside) < 0.0)
        n = -n;
    return vec4(n, 0.0);
}

vec4 g_planes[4];
vec3 g_corners[4];       // the tile's corner rays, as points on the near plane (view space)
float g_znear, g_zfar;   // view z of the range: g_znear >= z >= g_zfar (both negative)
bool g_boxed;            // g_zfar is finite: g_box_lo .. g_box_hi bounds the range
vec3 g_box_lo, g_box_hi;

// The range being culled against: view z from znear down to zfar (-inf: no far bound),
// and the view-space box around the tile's frustum between them (the corner rays at
// both depths). The four planes pass a sphere that lies off a corner of the tile (in
// reach of two planes' half-spaces but not of the frustum); the box test (the sphere's
// distance to the box) takes most of those out, as Olsson et al.'s clusters are tested
// against their boxes. Both tests are conservative: a light that meets the frustum
// between znear and zfar passes both.
void cull_range(float znear, float zfar)
{
    g_znear = znear;
    g_zfar = zfar;
    g_boxed = !isinf(zfar);
    if (!g_boxed)
        return;
    g_box_lo = vec3(uintBitsToFloat(0x7f800000u));   // +inf
    g_box_hi = -g_box_lo;
    for (int i = 0; i < 4; i++) {
        vec3 a = g_corners[i] * (znear / g_corners[i].z);
        vec3 b = g_corners[i] * (zfar / g_corners[i].z);
        g_box_lo = min(g_box_lo, min(a, b));
        g_box_hi = max(g_box_hi, max(a, b));
    }
}

bool sphere_passes(vec3 c, float r)
{
    if (c.z - r > g_znear || c.z + r < g_zfar)
        return false;
    for (int i = 0; i < 4; i++)
        if (dot(g_planes[i].xyz, c) < -r)
            return false;
    if (g_boxed) {
        vec3 d = max(max(g_box_lo - c, c - g_box_hi), vec3(0.0));
        if (dot(d, d) > r * r)
            return false;
    }
    return true;
}

// The sphere light i is culled as (false: a directional light, which passes every cell):
// point lights as their sphere (radius = range: light_cull_range, the frame's cut range
// with STOCHASTIC), spots as the smaller of that sphere and the cone's bounding sphere,
// a little larger than the range (conservative against rounding).
bool light_sphere(uint i, out vec3 c, out float r)
{
    Light l = b_lights[i];
    c = l.position_range.xyz;
    float range = light_cull_range(l);
    r = range;
#if HAS_SPOT || HAS_DIRECTIONAL
    int type = int(l.color_type.w);
#endif
#if HAS_DIRECTIONAL
    if (type == LIGHT_DIRECTIONAL)
        return false;
#endif
    float slack = 1e-4 * (range + length(c));
#if HAS_SPOT
    if (type == LIGHT_SPOT) {
        float cosa = l.direction_cos.w;
        if (cosa >= 0.5) {
            float t = range / (2.0 * cosa);
            c += l.direction_cos.xyz * t;
            r = t;
        }
    }
#endif
#ifdef COARSE_SIZE
    slack *= 10.0;   // a big tile keeps every light its tiles' tests (rounded) can pass
#endif
    r += slack;
    return true;
}

#ifdef DEPTH_MASK
// tiles.depth_culling: mask. While g_masked (the tile's own list, cull_tile), a sphere
// that passes the range must also cover a cell of g_mask, the cells the tile's samples
// occupy (tile_mask_cover): its extent in view z, c.z - r .. c.z + r, clamped to the
// tile's range, as cells (depth_cell, tiles.inc).
bool g_masked = false;
uint g_mask;
float g_cell_near, g_cell_scale;

bool sphere_meets_mask(vec3 c, float r)
{
    int lo = depth_cell(c.z + r, g_cell_near, g_cell_scale);
    int hi = depth_cell(c.z - r, g_cell_near, g_cell_scale);
    return !g_masked || (g_mask & (0xffffffffu >> uint(31 - hi)) & (0xffffffffu << uint(lo))) != 0u;
}
#endif

bool light_passes(uint i)
{
    vec3 c;
    float r;
#ifdef DEPTH_MASK
    return !light_sphere(i, c, r) || (sphere_passes(c, r) && sphere_meets_mask(c, r));
#else
    return !light_sphere(i, c, r) || sphere_passes(c, r);
#endif
}

#ifdef SLICES
// Olsson et al.'s spacing: log(1 + 2 tan(fov/2) / S_y), S_y = SLICES_Y (clustered.slices);
// tan(fov/2) = 1 / proj[1][1].
float slice_log_ratio()
{
    return log(1.0 + 2.0 / (f_proj[1][1] * float(SLICES_Y)));
}

// The slice of view depth z (negative): k = floor(log(-z/near) / log(1 + 2 tan(fov/2) /
// S_y)), clamped to the SLICES slices that reach the far plane (the first and the last
// are open towards the near and the far side, tile_cull.comp).
int slice_of(float z)
{
    return clamp(int(floor(log(-z / f_clip.x) / slice_log_ratio())), 0, SLICES - 1);
}

// View depth (positive) where slice k begins.
float slice_start(int k)
{
    return f_clip.x * exp(float(k) * slice_log_ratio());
}
#endif

const float DEPTH_WIDEN = 2.0 / 16777215.0;   // two steps of the 24-bit depth buffer

// The tile's depth range (view z, widened by two steps of the 24-bit depth buffer; -inf
// far when some pixel is at depth 1) from s_min_depth and s_max_depth.
void tile_depth_range(out float tile_znear, out float tile_zfar)
{
    float dmin = max(uintBitsToFloat(s_min_depth) - DEPTH_WIDEN, 0.0);
    float dmax = uintBitsToFloat(s_max_depth) + DEPTH_WIDEN;
    tile_znear = view_z(dmin);
    tile_zfar = dmax >= 1.0 ? uintBitsToFloat(0xff800000u) : view_z(dmax);   // -inf
}

// The tile's four planes into g_planes and its corner rays into g_corners, and its
// depth range (tile_depth_range).
#ifdef COARSE_SIZE
const uint CELL_PX = uint(COARSE_SIZE);   // a big tile's side
#else
const uint CELL_PX = uint(TILE_SIZE);
#endif

void tile_frustum(uvec2 tile, ivec2 size, out float tile_znear, out float tile_zfar)
{
    vec2 lo = vec2(tile * CELL_PX) / vec2(size) * 2.0 - 1.0;
    vec2 hi = vec2(min((tile + 1u) * CELL_PX, uvec2(size))) / vec2(size) * 2.0 - 1.0;
    vec3 c00 = view_at(lo, -1.0), c10 = view_at(vec2(hi.x, lo.y), -1.0);
    vec3 c11 = view_at(hi, -1.0), c01 = view_at(vec2(lo.x, hi.y), -1.0);
    vec3 inside = (c00 + c10 + c11 + c01) * 0.25;
    g_planes[0] = plane_through_eye(c00, c01, inside);   // left
    g_planes[1] = plane_through_eye(c10, c11, inside);   // right
    g_planes[2] = plane_through_eye(c00, c10, inside);   // bottom
    g_planes[3] = plane_through_eye(c01, c11, inside);   // top
    g_corners[0] = c00;
    g_corners[1] = c10;
    g_corners[2] = c11;
    g_corners[3] = c01;
    tile_depth_range(tile_znear, tile_zfar);
}

#ifdef DEPTH_MASK
// tiles.depth_culling: mask (Harada, McKee and Yang, "Forward+", EG 2012 short paper;
// GPU Pro 4's 2.5D culling). Once the tile's range is known (after tile_cover and a
// barrier), each invocation marks in s_depth_mask the cells (tiles.inc's depth_cell)
// its pixel's samples occupy, every sample at msaa > 1, each sample's depth widened by
// the range's two steps, so that the cells hold every depth the shading can see there;
// cull_tile calls it, with a barrier after.
uint sample_cells(float d, float znear, float scale)
{
    if (d >= 1.0)
        return 0u;   // no geometry
    if (scale == 0.0)
        return 1u;   // open range: one cell
    int lo = depth_cell(view_z(max(d - DEPTH_WIDEN, 0.0)), znear, scale);
    int hi = depth_cell(view_z(d + DEPTH_WIDEN), znear, scale);
    return (0xffffffffu >> uint(31 - hi)) & (0xffffffffu << uint(lo));
}

void tile_mask_cover(ivec2 pixel)
{
    if (!all(lessThan(pixel, ivec2(f_viewport.xy))))
        return;
    float znear, zfar;
    tile_depth_range(znear, zfar);
    float scale = depth_cell_scale(znear, zfar);
    uint bits = 0u;
#ifdef MSAA_SAMPLES
    for (int i = 0; i < MSAA_SAMPLES; i++)
        bits |= sample_cells(texelFetch(t_depth, pixel, i).r, znear, scale);
#else
    bits = sample_cells(texelFetch(t_depth, pixel, 0).r, znear, scale);
#endif
    if (bits != 0u)
        atomicOr(s_depth_mask, bits);
}
#endif

// Culls every light against the planes and [g_zfar, g_znear] into cell `cell`'s list,
// in light order. Called by the whole work group with the same arguments. The passing
// lights set their bit in s_bits; each invocation counts the bits of its run of words,
// invocation 0 makes the exclusive prefix of the runs' counts and takes the list's
// place in the index buffer with one atomicAdd (place_list), and each invocation pops
// its words' bits and writes them at its place. Up to CHUNK candidates every light is
// tested once, with four barriers (barriers are what a software rasterizer pays for);
// beyond, the candidates are counted first and then written CHUNK at a time.
// from_list: the candidates are b_indices[src .. src + nlights) (a list written
// earlier in this dispatch by this work group: the tile's, for its clusters) rather
// than the lights 0 .. nlights. cell NO_CELL: no b_tiles entry, the list's place and
// length stay in s_offset and s_count (0xffffffff: it did not fit).
const uint NO_CELL = 0xffffffffu;

#ifdef COARSE_LISTS
bool g_from_coarse = false;   // from_list: the list is the big tile's (cull_tile)
#endif

uint candidate(uint e, uint src, bool from_list)
{
#ifdef COARSE_LISTS
    if (from_list && g_from_coarse)
        return b_coarse_indices[src + e];
#endif
    return from_list ? b_indices[src + e] : e;
}

#ifdef MSAA_SAMPLES
// The nearest (d) and farthest (d_far) depth of the pixel's samples that have geometry;
// 1 and 0 when none has (t_depth: the multisampled depth target).
void pixel_depth_range(ivec2 pixel, out float d, out float d_far)
{
    d = 1.0;
    d_far = 0.0;
    for (int i = 0; i < MSAA_SAMPLES; i++) {
        float di = texelFetch(t_depth, pixel, i).r;
        if (di < 1.0) {
            d = min(d, di);
            d_far = max(d_far, di);
        }
    }
}
#endif

#ifdef PRUNE_SAMPLES
// tiles.prune: samples (Unity HDRP's fine pruning of its FPTL tiles). Each invocation
// holds its pixel's samples as a view-space box (pixel_samples_box): the pixel's
// centre ray (msaa > 1: its four corner rays, every sample position) between its
// nearest and farthest sample depth, each widened by the range's two steps; no box
// (g_px_valid false) without geometry. While g_pruned (the tile's own list, cull_tile),
// cull_bits' passing lights are then pruned word by word (prune_bits): each invocation
// tests the word's lights against its box, the hits are ORed into a shared word, and
// a light no pixel's box meets is dropped, so the list keeps every light that reaches
// a position the shading can reconstruct from the tile's depth.
bool g_pruned = false;
bool g_px_valid;
vec3 g_px_lo, g_px_hi;

void pixel_samples_box(ivec2 pixel)
{
    g_px_valid = false;
    if (!all(lessThan(pixel, ivec2(f_viewport.xy))))
        return;
#ifdef MSAA_SAMPLES
    float d, d_far;
    pixel_depth_range(pixel, d, d_far);
    vec2 lo = vec2(pixel), hi = lo + 1.0;
#else
    float d = texelFetch(t_depth, pixel, 0).r, d_far = d;
    vec2 lo = vec2(pixel) + 0.5, hi = lo;
#endif
    if (d >= 1.0)
        return;
    g_px_valid = true;
    float zn = view_z(max(d - DEPTH_WIDEN, 0.0)), zf = view_z(min(d_far + DEPTH_WIDEN, 1.0));
    vec2 size = f_viewport.xy;
    vec3 r[4] = vec3[4](view_at(lo / size * 2.0 - 1.0, -1.0),
                        view_at(vec2(hi.x, lo.y) / size * 2.0 - 1.0, -1.0),
                        view_at(hi / size * 2.0 - 1.0, -1.0),
                        view_at(vec2(lo.x, hi.y) / size * 2.0 - 1.0, -1.0));
    g_px_lo = vec3(uintBitsToFloat(0x7f800000u));
    g_px_hi = -g_px_lo;
    for (int i = 0; i < 4; i++) {
        vec3 a = r[i] * (zn / r[i].z), b = r[i] * (zf / r[i].z);
        g_px_lo = min(g_px_lo, min(a, b));
        g_px_hi = max(g_px_hi, max(a, b));
    }
}

// The lights of word w's bits `b` (candidates first .. first + 31) whose volume meets
// this invocation's pixel box; a directional light meets every box.
uint pixel_hits(uint b, uint first, uint src, bool from_list)
{
    uint hits = 0u;
    if (!g_px_valid)
        return 0u;
    while (b != 0u) {
        int j = findLSB(b);
        b &= b - 1u;
        vec3 c;
        float r;
        if (light_sphere(candidate(first + uint(j), src, from_list), c, r)) {
            vec3 d = max(max(g_px_lo - c, c - g_px_hi), vec3(0.0));
            if (dot(d, d) > r * r)
                continue;
        }
        hits |= 1u << uint(j);
    }
    return hits;
}

// Keeps in s_bits[0 .. words) only the lights some pixel's box meets (candidates from
// base on); one barrier a non-empty word: the hits of word k are ORed into s_hit[k & 1]
// while invocation 0 clears the other for the next word.
void prune_bits(uint base, uint words, uint src, bool from_list)
{
    uint me = gl_LocalInvocationIndex;
    if (me == 0u)
        s_hit[0] = 0u;
    barrier();
    uint k = 0u;
    for (uint w = 0u; w < words; w++) {
        uint b = s_bits[w];   // uniform: only invocation 0 rewrites it, after the barrier
        if (b == 0u)
            continue;
        uint mine = pixel_hits(b, base + w * 32u, src, from_list);
        if (me == 0u)
            s_hit[(k + 1u) & 1u] = 0u;
        if (mine != 0u)
            atomicOr(s_hit[k & 1u], mine);
        barrier();
        if (me == 0u)
            s_bits[w] = s_hit[k & 1u];
        k++;
    }
    barrier();
}
#endif

// Invocation 0: the place of a list of `count` lights in the index buffer (s_offset,
// 0xffffffff when it does not fit; s_count) and cell's b_tiles entry.
void place_list(uint cell, uint covered, uint count)
{
    uint offset = count == 0u ? 0u : atomicAdd(b_stats.next, count);
    bool fits = offset <= b_stats.capacity && count <= b_stats.capacity - offset;
    s_count = count;
    s_offset = fits ? offset : 0xffffffffu;
    if (cell != NO_CELL)
        b_tiles[cell] = uvec4(fits ? offset : 0u, fits ? count : 0u, covered, count);
}

// Sets the bits of the candidates base .. end that pass (s_bits cleared up to `words`).
void cull_bits(uint base, uint end, uint words, uint src, bool from_list)
{
    uint me = gl_LocalInvocationIndex;
    for (uint w = me; w < words; w += N)
        s_bits[w] = 0u;
    barrier();
    for (uint i = base + me; i < end; i += N) {
        uint c = candidate(i, src, from_list);
#ifdef ZBIN_BINS
        uint at = c;   // zbin: a bit per sorted light (base 0), whatever the candidates
#else
        uint at = i - base;
#endif
        if (light_passes(c))
            atomicOr(s_bits[at >> 5], 1u << (at & 31u));
    }
    barrier();
#if defined(PRUNE_SAMPLES) && defined(ZBIN_BINS)
    if (g_pruned)
        prune_bits(0u, words, 0u, false);   // the bits are the lights'
#elif defined(PRUNE_SAMPLES)
    if (g_pruned)
        prune_bits(base, words, src, from_list);
#endif
}

// Each invocation's run of the first `words` words of s_bits: s_part[me] = its count,
// returned as [w0, w1); invocation 0 then turns s_part into an exclusive prefix over
// the runs (only the runs that hold words) and returns the total in s_chunk.
uvec2 count_runs(uint words)
{
    uint me = gl_LocalInvocationIndex;
    uint per = (words + N - 1u) / N;   // words each invocation owns
    uint w0 = min(me * per, words), w1 = min(w0 + per, words);
    uint c = 0u;
    for (uint w = w0; w < w1; w++)
        c += uint(bitCount(s_bits[w]));
    s_part[me] = c;
    barrier();
    if (me == 0u) {
        uint runs = per == 0u ? 0u : (words + per - 1u) / per;
        uint sum = 0u;
        for (uint k = 0u; k < runs; k++) {
            uint v = s_part[k];
            s_part[k] = sum;
            sum += v;
        }
        s_chunk = sum;
    }
    return uvec2(w0, w1);
}

// Writes the passing candidates of the invocation's run of words, from index pos on.
void write_run(uvec2 run, uint base, uint pos, uint src, bool from_list)
{
    for (uint w = run.x; w < run.y; w++) {
        uint b = s_bits[w];
        while (b != 0u) {
            int j = findLSB(b);
            b &= b - 1u;
            b_indices[pos++] = candidate(base + w * 32u + uint(j), src, from_list);
        }
    }
}

#ifdef PRUNE_SAMPLES
#define PRUNED g_pruned
#else
#define PRUNED false
#endif

void cull_cell(uint cell, uint covered, uint nlights, uint src, bool from_list)
{
    uint me = gl_LocalInvocationIndex;
    barrier();   // s_bits and s_part may still be read by the last call
    if (nlights <= CHUNK) {   // one test per candidate
        uint words = (nlights + 31u) / 32u;
        cull_bits(0u, nlights, words, src, from_list);
        uvec2 run = count_runs(words);
        if (me == 0u)
            place_list(cell, covered, s_chunk);
        barrier();
        if (s_offset != 0xffffffffu && s_count > 0u)
            write_run(run, 0u, s_offset + s_part[me], src, from_list);
        return;
    }
    if (me == 0u)
        s_count = 0u;
    barrier();
#ifdef PRUNE_SAMPLES
    if (g_pruned) {   // counted chunk by chunk, pruned as they will be written
        for (uint base = 0u; base < nlights; base += CHUNK) {
            cull_bits(base, min(base + CHUNK, nlights), WORDS, src, from_list);
            count_runs(WORDS);
            barrier();
            if (me == 0u)
                s_count += s_chunk;
            barrier();
        }
    }
#endif
    uint mine = 0u;
    for (uint i = me; i < nlights; i += N)
        if (!PRUNED && light_passes(candidate(i, src, from_list)))
            mine++;
    if (mine > 0u)
        atomicAdd(s_count, mine);
    barrier();
    if (me == 0u)
        place_list(cell, covered, s_count);
    barrier();
    uint offset = s_offset, count = s_count;
    if (offset == 0xffffffffu || count == 0u)
        return;   // uniform across the work group
    uint written = 0u;
    for (uint base = 0u; base < nlights; base += CHUNK) {
        cull_bits(base, min(base + CHUNK, nlights), WORDS, src, from_list);
        uvec2 run = count_runs(WORDS);
        barrier();
        write_run(run, base, offset + written + s_part[me], src, from_list);
        written += s_chunk;
        barrier();
    }
}

#ifdef SLICES
shared float s_slice_near[SLICES], s_slice_far[SLICES];   // the ranges culled against
shared uint s_cluster_count[SLICES], s_cluster_first[SLICES];

// The tile's clusters: the tile's own list first (over every light, into the index
// buffer, not a cell of its own), then each slice the tile's depth range meets (one
// more on either side) culled from that list against the slice's depth range (widened
// by 1e-3; the first slice open towards the near side, the last towards the far), the
// others written empty. Cells are numbered k x TILES_X x TILES_Y + tile.
// All the tile's slices are culled together, with a fixed number of barriers (not a
// cull_cell per slice: on llvmpipe a barrier switches every SIMD group of the work
// group, and a tile meets up to SLICES slices): each invocation takes a light of the
// tile's list and tests it against the slices its depth extent can meet (a bit per
// slice and light in s_bits, slice j's bits in words j x W .. j x W + W - 1, W =
// ceil(n / 32)); then the slices' counts, one place in the index buffer for all of
// them (invocation 0), and the lists written word by word, each in the tile list's
// (light) order. A tile whose slices' bits would not fit s_bits (n x slices > CHUNK)
// takes the slices one by one.
void cull_clusters(uint tile_index, uint covered, uint nlights, uint from, bool from_list,
                   float tile_znear, float tile_zfar)
{
    uint me = gl_LocalInvocationIndex;
    uint ntiles = uint(TILES_X * TILES_Y);
    cull_cell(NO_CELL, covered, nlights, from, from_list);
#ifdef COARSE_LISTS
    g_from_coarse = false;   // the clusters are cut from the tile's list
#endif
#ifdef DEPTH_MASK
    g_masked = false;   // the clusters are cut from the masked tile list
#endif
#ifdef PRUNE_SAMPLES
    g_pruned = false;   // and from the pruned one
#endif
    memoryBarrierBuffer();
    barrier();
    uint src = s_offset, n = s_offset == 0xffffffffu ? 0u : s_count;
    barrier();
    int kmin = 0, kmax = -1;   // no geometry: every cluster empty
    if (covered > 0u) {
        kmin = max(slice_of(tile_znear) - 1, 0);
        kmax = isinf(tile_zfar) ? SLICES - 1 : min(slice_of(tile_zfar) + 1, SLICES - 1);
    }
    for (uint k = me; k < uint(SLICES); k += N) {
        if (int(k) < kmin || int(k) > kmax) {
            b_tiles[k * ntiles + tile_index] = uvec4(0u);
            continue;
        }
        const float EPS = 1e-3;
        int i = int(k);
        s_slice_near[k] = i == 0 ? tile_znear : min(tile_znear, -slice_start(i) * (1.0 - EPS));
        s_slice_far[k] = i == SLICES - 1 ? tile_zfar
                                         : max(tile_zfar, -slice_start(i + 1) * (1.0 + EPS));
    }
    barrier();
    uint nslices = uint(kmax - kmin + 1);
    uint per_slice = (n + 31u) / 32u;   // words of one slice's bits
    uint words = nslices * per_slice;
    if (words > WORDS) {
        for (int k = kmin; k <= kmax; k++) {
            cull_range(s_slice_near[k], s_slice_far[k]);
            cull_cell(uint(k) * ntiles + tile_index, s_slice_covered[k], n, src, true);
        }
        return;
    }
    for (uint w = me; w < words; w += N)
        s_bits[w] = 0u;
    barrier();
    for (uint e = me; e < n; e += N) {   // each light of the tile's list
        vec3 c;
        float r;
        bool sphere = light_sphere(b_indices[src + e], c, r);
        // the slices its depth extent meets, its ends moved by the ranges' widening
        // (1 +- 1e-3), one more either side against rounding, depths nearer than the
        // near plane taken as on it (slice 0): no other slice's depth test can pass
        int lo = kmin, hi = kmax;
        if (sphere) {
            const float EPS = 1e-3;
            float zn = min((c.z + r) / (1.0 + EPS), -f_clip.x);
            float zf = min((c.z - r) / (1.0 - EPS), -f_clip.x);
            lo = max(kmin, slice_of(zn) - 1);
            hi = min(kmax, slice_of(zf) + 1);
        }
        for (int k = lo; k <= hi; k++) {
            cull_range(s_slice_near[k], s_slice_far[k]);
            if (!sphere || sphere_passes(c, r))
                atomicOr(s_bits[uint(k - kmin) * per_slice + (e >> 5)], 1u << (e & 31u));
        }
    }
    barrier();
    for (uint j = me; j < nslices; j += N) {
        uint count = 0u;
        for (uint w = j * per_slice; w < (j + 1u) * per_slice; w++)
            count += uint(bitCount(s_bits[w]));
        s_cluster_count[j] = count;
    }
    barrier();
    if (me == 0u) {   // one place for the tile's clusters, each list after the last
        uint total = 0u;
        for (uint j = 0u; j < nslices; j++)
            total += s_cluster_count[j];
        uint offset = total == 0u ? 0u : atomicAdd(b_stats.next, total);
        bool fits = offset <= b_stats.capacity && total <= b_stats.capacity - offset;
        for (uint j = 0u; j < nslices; j++) {
            uint k = uint(kmin) + j, count = s_cluster_count[j];
            s_cluster_first[j] = offset;
            b_tiles[k * ntiles + tile_index] = uvec4(fits ? offset : 0u, fits ? count : 0u,
                                                     s_slice_covered[k], count);
            offset += count;
        }
        s_offset = fits ? 0u : 0xffffffffu;
    }
    barrier();
    if (s_offset == 0xffffffffu)
        return;   // uniform: nothing written, the frame fails (b_stats.next > capacity)
    for (uint w = me; w < words; w += N) {
        uint j = w / per_slice, first = w - j * per_slice;   // first: the word in the slice
        uint pos = s_cluster_first[j];
        for (uint v = w - first; v < w; v++)
            pos += uint(bitCount(s_bits[v]));
        uint b = s_bits[w];
        while (b != 0u) {
            int bit = findLSB(b);
            b &= b - 1u;
            b_indices[pos++] = b_indices[src + first * 32u + uint(bit)];
        }
    }
}
#endif

#ifdef TLISTS
// The tile's translucent list (issue 12; van Oosten's transparent lists, "the camera's
// near plane" instead of the tile's min depth): the lights whose volume meets the
// tile's four planes between the camera's near plane and the tile's largest opaque
// depth (what lies behind it is hidden), or the far side when some pixel of the tile
// has no geometry (a pane can be seen over the sky there at any depth). Every light
// is tested, covered tile or not, into the same index buffer (the same allocator and
// overflow rule as the opaque lists); the head is b_tiles[TLISTS + tile], TLISTS being
// the number of opaque cells. Called by the whole work group after the opaque lists,
// with g_planes still the tile's.
void cull_translucent(uvec2 tile, uint tile_index, ivec2 size, uint covered, float tile_zfar)
{
    uvec2 lo = tile * uint(TILE_SIZE);
    uvec2 hi = min(lo + uint(TILE_SIZE), uvec2(size));
    uint pixels = (hi.x - lo.x) * (hi.y - lo.y);
    cull_range(-f_clip.x, covered == pixels ? tile_zfar : uintBitsToFloat(0xff800000u));
    barrier();
    cull_cell(uint(TLISTS) + tile_index, covered, uint(u_light_count), 0u, false);
}
#endif

#ifdef ZBIN_BINS
shared uint s_evals;
// zbin (zbin.inc): the tile keeps a bit mask over the sorted lights, not a list. Its
// lights are tested as a list's would be (cull_bits: the range, DEPTH_MASK's cells,
// PRUNE_SAMPLES' boxes) and the bits written as its mask (the words the frame's lights
// need); b_tiles[tile] = (evaluations summed over its pixels, lights, covered pixels,
// lights), each pixel with geometry counting what zbin_next gives it at its nearest
// sample's depth: the directional lights and its mask's bits within its bin.
void zbin_cull_tile(uint tile_index, uint covered, uint nlights, uint src, bool from_list,
                    ivec2 pixel)
{
    uint me = gl_LocalInvocationIndex;
    uint words = z_words;
    barrier();
    if (me == 0u) {
        s_evals = 0u;
        s_count = 0u;
    }
    cull_bits(0u, nlights, words, src, from_list);
    for (uint w = me; w < words; w += N) {
        uint b = s_bits[w];
        b_zmasks[tile_index * words + w] = b;
        if (b != 0u)
            atomicAdd(s_count, uint(bitCount(b)));
    }
    if (all(lessThan(pixel, ivec2(f_viewport.xy)))) {
#ifdef MSAA_SAMPLES
        float d, d_far;
        pixel_depth_range(pixel, d, d_far);
#else
        float d = texelFetch(t_depth, pixel, 0).r;
#endif
        if (d < 1.0) {
            uint bin = b_zbins[zbin_of(view_z(d))];
            uint lo = bin & 0xffffu, hi = bin >> 16, e = z_directional;
            for (uint w = lo >> 5; lo <= hi && w <= (hi >> 5); w++)
                e += uint(bitCount(zbin_clip(s_bits[w], w, lo, hi)));
            atomicAdd(s_evals, e);
        }
    }
    barrier();
    if (me == 0u)
        b_tiles[tile_index] = uvec4(s_evals, s_count, covered, s_count);
}
#endif

// Once the work group has covered the tile (tile_cover, then a barrier), each
// invocation with its pixel: (DEPTH_MASK) the cells its samples occupy
// (tile_mask_cover, then a barrier); the tile's frustum, and the light lists of its cell
// or its clusters (SLICES) and its translucent list (TLISTS), culled by the whole work
// group. TILE_DEPTH_RANGES keeps the range culled against for the shading pass's fallback.
// PRUNE_SAMPLES: the tile's list pruned by its pixels' boxes (prune_bits); COARSE_LISTS:
// its candidates are its big tile's list rather than every light.
void cull_tile(ivec2 pixel)
{
#ifdef DEPTH_MASK
    tile_mask_cover(pixel);
    barrier();
#endif
    uvec2 tile = gl_WorkGroupID.xy;
    uint tile_index = tile.y * uint(TILES_X) + tile.x;
    ivec2 size = ivec2(f_viewport.xy);
    uint covered = s_covered;
    uint nlights = covered == 0u ? 0u : uint(u_light_count);
    float tile_znear, tile_zfar;
    tile_frustum(tile, size, tile_znear, tile_zfar);
#if defined(TILE_DEPTH_RANGES) && defined(DEPTH_MASK)
    if (gl_LocalInvocationIndex == 0u)
        b_tile_depth[tile_index] = uvec4(floatBitsToUint(vec2(tile_znear, tile_zfar)),
                                         s_depth_mask, 0u);
#elif defined(TILE_DEPTH_RANGES)
    if (gl_LocalInvocationIndex == 0u)
        b_tile_depth[tile_index] = vec2(tile_znear, tile_zfar);
#endif
    cull_range(tile_znear, tile_zfar);
#ifdef DEPTH_MASK
    g_mask = s_depth_mask;   // the tile's own list only: not its translucent one
    g_cell_near = tile_znear;
    g_cell_scale = depth_cell_scale(tile_znear, tile_zfar);
    g_masked = true;
#endif
#ifdef PRUNE_SAMPLES
    pixel_samples_box(pixel);
    g_pruned = true;   // the tile's own list only: not its translucent one
#endif
    uint from = 0u;
    bool from_list = false;
#ifdef COARSE_LISTS
    // tiles.levels: 2: the big tile's list, a superset of what the tile keeps (every
    // light when the big tile's did not fit: y < w)
    uvec4 big = b_coarse_tiles[(tile.y / uint(COARSE_LISTS)) *
                               ((uint(TILES_X) + uint(COARSE_LISTS) - 1u) / uint(COARSE_LISTS)) +
                               tile.x / uint(COARSE_LISTS)];
    if (nlights > 0u && big.y == big.w) {
        from = big.x;
        from_list = true;
        nlights = big.y;
        g_from_coarse = true;
    }
#endif
#if defined(ZBIN_BINS)
    zbin_cull_tile(tile_index, covered, nlights, from, from_list, pixel);   // a mask
#elif !defined(SLICES)
    cull_cell(tile_index, covered, nlights, from, from_list);
#else
    cull_clusters(tile_index, covered, nlights, from, from_list, tile_znear, tile_zfar);
#endif
#ifdef COARSE_LISTS
    g_from_coarse = false;
#endif
#ifdef DEPTH_MASK
    g_masked = false;
#endif
#ifdef PRUNE_SAMPLES
    g_pruned = false;
#endif
#ifdef TLISTS
    cull_translucent(tile, tile_index, size, covered, tile_zfar);
#endif
}
