/* canyon: seed 000's exterior scene (section 4.8.1): "a large exterior canyon area",
 * with "a large draw distance (8192 units)", "an ambient light source", "a non shadow
 * casting directional light source (the sun)" and "4 relatively high poly terrain
 * meshes, each with diffuse, specular and normal maps".
 *
 * Units, the terrain, the camera and the random lights' bounds: the comment above the
 * terrain's constants below. */
#include "scenes/scene_build.h"

#include <math.h>

/* Units: 1 world unit = 1 metre here (seed 000's units are its engine's; only the 8192
 * matters). The terrain is 8192 x 8192 units, four 4096 x 4096 tiles of 128 x 128 cells
 * (32 units a cell, 32768 triangles each, 131072 in all) about the origin: a valley
 * running along Z whose floor (|x - meander(z)| < 400, height within +-30 of 0) winds
 * 350 either side of x = 0, walls rising to 1100 between 400 and 1600 from its centre
 * line, and fractal noise over all (+-30 on the floor, +-180 on the plateaus). The tiles
 * sample one height function at their world coordinates, so their borders meet exactly.
 *
 * The camera orbits the valley's middle at radius 3000, 1300 above a target 400 above the
 * floor (eye 1700 above the floor, clear of the plateaus' 1280 at most), looking down 23
 * degrees, so the upper part of the screen reaches across the terrain: its far edge is
 * 7100 to 8800 units away depending on the orbit angle; at the diagonals (t = 7.5 s,
 * 22.5 s, ...) the far plane (view depth 8192) cuts it, and the sky shows beyond. This is
 * the scene for G-buffer position precision at long range.
 *
 * Random lights go along the valley floor: x in [-750, 750], y in [0, 500], z in
 * [-4000, 4000]. At this scale 1/d^2 lights of colour 0.3 are invisible beyond 9 units, so
 * runs with random lights here want linear-range attenuation with a radius in the
 * hundreds: 160 lights reach a point of the bounds once on average at radius 207
 * (lights.overlap: 1 gives it). */
#define CANYON_TILE 4096.0f
#define CANYON_CELLS 128u

typedef struct canyon_terrain {
    mesh_terrain noise;        /* heights in [-1, 1] (height scale 1) */
    float ox, oz;              /* the tile's centre: local (x, z) + (ox, oz) = world */
} canyon_terrain;

/* The valley's centre line: x = 350 sin(2 pi 1.5 z / 8192). */
static float canyon_meander(float z)
{
    return 350.0f * sinf(2.0f * (float)SM_PI * 1.5f * z / (2.0f * CANYON_TILE));
}

static float canyon_height(float x, float z, void *user)
{
    canyon_terrain *t = user;
    float wx = x + t->ox, wz = z + t->oz;
    float d = fabsf(wx - canyon_meander(wz));
    float w = sm_clamp((d - 400.0f) / 1200.0f, 0.0f, 1.0f);
    w = w * w * (3.0f - 2.0f * w);   /* smoothstep: floor 0, plateau 1 */
    float n = mesh_terrain_height(wx, wz, &t->noise);
    return 1100.0f * w + (30.0f + 150.0f * w) * n;
}

bool scene_build_canyon(scene_builder *b, const void *arg)
{
    scene *s = b->s;
    if (!sb_begin(b, 4))
        return false;
    /* four sandstone hues: each tile its own diffuse, gloss and normal maps */
    static const float hue[4][2][3] = {
        {{0.55f, 0.38f, 0.25f}, {0.82f, 0.66f, 0.48f}},
        {{0.54f, 0.38f, 0.26f}, {0.81f, 0.65f, 0.48f}},
        {{0.56f, 0.39f, 0.25f}, {0.83f, 0.67f, 0.49f}},
        {{0.55f, 0.37f, 0.24f}, {0.82f, 0.65f, 0.47f}},
    };
    canyon_terrain terrain[4];
    for (int k = 0; k < 4; k++) {
        texture_desc rock = {.width = 256, .height = 256, .pattern = TEXTURE_NOISE, .cells = 8,
                             .seed = 8192u + (uint32_t)k, .noise = 0.7f, .bump = 3.0f,
                             .gloss_a = 0.35f, .gloss_b = 0.1f};
        for (int c = 0; c < 3; c++) {
            rock.color_a[c] = hue[k][0][c];
            rock.color_b[c] = hue[k][1][c];
        }
        sb_map_set maps = sb_maps(b, &rock, false);
        uint32_t mat = sb_material_maps(b, &maps, 0.25f, 12.0f, 0.0f);
        /* tile k: x towards +X for odd k, z towards +Z for k >= 2 */
        canyon_terrain *t = &terrain[k];
        mesh_terrain_init(&t->noise, 2.0f * CANYON_TILE, 2.0f * CANYON_TILE, 1.0f, 1987u);
        t->ox = (k % 2 ? 0.5f : -0.5f) * CANYON_TILE;
        t->oz = (k / 2 ? 0.5f : -0.5f) * CANYON_TILE;
        int m = sb_heightfield(b, CANYON_TILE, CANYON_TILE, CANYON_CELLS, CANYON_CELLS,
                               canyon_height, t);
        sb_mesh_uv_scale(b, m, 16.0f, 16.0f);   /* the maps repeat every 256 units */
        sb_object(b, m, mat, t->ox, 0.0f, t->oz, 1.0f);
    }
    /* the sun: low in the west-south-west, warm; never casts shadows (seed 000: a
     * shadowing sun would need very high-resolution or trapezoidal shadow maps here) */
    sm_vec3 sun_dir = {0.55f, -0.6f, 0.35f}, sun = {1.0f, 0.93f, 0.8f};
    sb_directional(b, sun_dir, sun, false);
    sm_vec3_make(0.22f, 0.24f, 0.28f, s->ambient);
    sb_set_sky(b, 0.55f, 0.7f, 0.9f);
    sb_set_bounds(b, -750.0f, 0.0f, -4000.0f, 750.0f, 500.0f, 4000.0f);
    sb_set_orbit(b, 0.0f, 400.0f, 0.0f, 3000.0f, 1300.0f, 60.0f);
    sb_set_projection(b, 60.0f, 1.0f, 8192.0f);
    return !b->failed;
}
