#pragma once
/* The frontend (DOOM 3 BFG's split): what to draw this frame, decided once and
 * shared by every renderer; the backends only execute it.
 * Its fields (visible, translucent, lights, illum, eye_inside, shadow), the
 * matrices its tests use, the light volumes and what it allocates: the comment
 * above FRONTEND_VOLUME_SCALE below. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "scenes/scene.h"

/* What frontend_build() decides each frame, in struct frontend:
 *
 *   visible   opaque objects (material not MATERIAL_BLEND) whose world bounding
 *             sphere is not outside the view frustum, sorted into state buckets: by diffuse map, then material,
 *             then mesh (seed 000 4.4.3 sorts by diffuse texture); ties (objects
 *             with the same key) keep their object order
 *   translucent  the visible objects of MATERIAL_BLEND materials (same frustum
 *             test), sorted back to front: by the view depth of their bounding
 *             sphere's centre (-z in view space), farthest first; equal depths keep
 *             object order. Not in `visible`, in no illumination set and in no
 *             shadow-casting set (translucent objects cast no shadows): every
 *             renderer draws them in its translucent pass (renderers/frame/translucent.h),
 *             lit by the frame's `lights`
 *   lights    active lights (scene.lights[0 .. nlights_active)) that can light
 *             something visible, in light order: directional lights always; a point
 *             light when its sphere (position, radius) is not outside the frustum; a
 *             spot light when the bounding sphere of its cone (apex at the light,
 *             axis along its direction, half angle spot_angle, height radius:
 *             frontend_spot_cone_bound) is not outside the frustum
 *   illum     per light, its illumination set (seed 000 4.6): the visible objects
 *             whose bounding sphere intersects the light's volume, in `visible`
 *             order: point lights sphere against sphere (sm_sphere_sphere_intersects
 *             with (position, radius)); spots sm_cone_sphere_intersects(position,
 *             direction, spot_angle, radius); directional lights every visible object
 *   eye_inside per light: 1 when the light's volume mesh AS DRAWN (scene_gpu, see
 *             "Light volumes" below) may contain the eye or be cut by the near
 *             plane, so that a volume pass must not rely on its front faces: the
 *             eye is within the bounding sphere of the drawn volume
 *             (frontend_light_volume_bound), or that sphere reaches the near plane's
 *             rectangle (the near face of the view frustum). Conservative: it may say
 *             1 for a volume that comes close without being cut, never 0 for one that
 *             is. Directional lights: always 1 (they have no volume; a full-screen
 *             pass).
 *
 *   shadow    per light, its shadow-casting set (seed 000 4.4.4) when the light casts
 *             shadows this frame (frontend_light_casts_shadows, and no_shadows is
 *             false): it gets the next layer of the renderer's shadow-map pool
 *             (shadow_layer, 0, 1, ... in light order; FRONTEND_NO_SHADOW for every
 *             other light, whose set is empty), the matrix its map is drawn with
 *             (shadow_viewproj, world to the light's clip space) and the objects drawn
 *             into its map. A light whose illumination set is empty gets a layer and
 *             an empty set: it lights nothing that is seen, so no shadow of it is
 *             either. Otherwise:
 *               spot, centre (position) inside the view frustum (on no plane's
 *                 outside, sm_plane_distance >= 0 for all six): its illumination set,
 *                 i.e. the visible objects whose bounding sphere meets its cone. Seed
 *                 000 4.4.4's first case (after O'Rorke): shadows are cast away from
 *                 the light, the frustum is convex, so a caster of a visible shadow
 *                 lies on a segment from the light to a visible point, inside the
 *                 frustum: it is visible. In `visible` order.
 *               spot, centre outside the frustum: every object of the scene (visible
 *                 or not) whose bounding sphere meets the cone, in object order. For
 *                 this case seed 000 4.4.4 put every mesh of the scene in the set (brute
 *                 force; its convex hull of frustum and light was left unfinished). An
 *                 object outside the cone can cast no shadow of this light (its map
 *                 covers the cone only), so this is the paper's set less what cannot
 *                 matter, and still a superset of what does: it draws fewer objects
 *                 than the paper did, and seed 000 5.3 names that set's excess as why
 *                 its shadows-on draw counts are high.
 *               directional: the receivers are the visible objects; in the light's
 *                 view (sm_look from the origin along the light's direction, up +Y)
 *                 their bounding spheres span the rectangle R = [x0, x1] x [y0, y1] and
 *                 the depths (distance along the direction) up to dmax. The set is
 *                 every object of the scene whose sphere's disc (centre xy, radius r)
 *                 meets R and whose nearest depth (centre depth - r) is <= dmax: a
 *                 shadow moves along the direction, keeping x and y, so nothing
 *                 outside R or wholly beyond every receiver can fall on one. Object
 *                 order. (The paper's scenes had one directional light, and its
 *                 interior moon cast shadows; it does not say what set it used.)
 *             Spot maps: perspective from the light along its direction (sm_look, up
 *             +Y), fovy = 2 x spot_angle (clamped as for volumes), aspect 1, near =
 *             radius / 1000, far = radius: the cone is inscribed in the map.
 *             Directional maps: sm_ortho over R and depths [dmin, dmax] (dmin the
 *             nearest depth of the set and the receivers), each side widened by 1% of
 *             its extent (at least 1e-3) so that nothing is clipped by rounding.
 *
 * All tests use the matrices scene_update() posed: planes from scene.viewproj
 * (sm_frustum_planes), the eye from the inverse of scene.view, the near rectangle
 * from the inverse of scene.viewproj (sm_frustum_corners); scene.cam is not read, so
 * a test may set view / proj / viewproj directly.
 *
 * Light volumes (what scene_gpu draws, shared here so that eye_inside and the drawn
 * mesh agree): a point light's volume is mesh_light_sphere(FRONTEND_SPHERE_SLICES,
 * FRONTEND_SPHERE_STACKS), which holds the unit sphere, scaled by radius x
 * FRONTEND_VOLUME_SCALE (1.1, seed 000 appendix C) about the light; its vertices lie
 * at radius x 1.1 x f->sphere_vertex_radius (1.0389 for 16 x 8). A spot's volume is ONE
 * unit cone, mesh_light_cone(pi/4, FRONTEND_CONE_SEGMENTS) (which holds the 45-degree
 * cone of height 1), scaled non-uniformly by (radius tan(spot_angle), radius
 * tan(spot_angle), radius), so that it holds the spot's cone of height radius (and so
 * the lit region, points within `radius` inside the cone), -Z rotated onto the spot's
 * direction, apex at the light (frontend_light_volume_model). spot_angle must be in
 * (0, pi/2); it is clamped to [1e-4, pi/2 - 1e-3] for volumes and bounds.
 *
 * Counts here are what work-count tests derive their formulas from. Nothing is
 * allocated by frontend_build() unless the scene grew since the last call (more
 * objects or lights than any frame before, or more illumination or shadow-set entries
 * than the reserve: capacities only grow). */
#define FRONTEND_VOLUME_SCALE 1.1f
enum {
    FRONTEND_SPHERE_SLICES = 16,
    FRONTEND_SPHERE_STACKS = 8,
    FRONTEND_CONE_SEGMENTS = 16,
};

/* Scratch for the sort (2 x cap_objects: a stable merge sort, no allocation). */
typedef struct frontend_sort_item {
    uint64_t key;
    uint32_t object;
} frontend_sort_item;

typedef struct frontend {
    sm_vec4 planes[6];         /* the view frustum (sm_frustum_planes order) */
    uint32_t *visible;         /* object indices, sorted */
    uint32_t nvisible;
    uint32_t *translucent;     /* object indices, back to front (see above) */
    uint32_t ntranslucent;
    uint32_t *lights;          /* light indices (into scene.lights), in light order */
    uint32_t nlights;
    uint32_t *illum_start;     /* nlights + 1 offsets into illum */
    uint32_t *illum;           /* object indices */
    uint32_t *eye_inside;      /* per light in `lights`: 1 when the eye is inside its volume
                                  (or the near plane cuts it), for light-volume passes */
    size_t cap_objects, cap_lights, cap_illum;

    /* Added: */
    sm_vec3 eye;               /* world space, from the inverse of scene.view */
    sm_vec4 near_corners[4];   /* the near rectangle, world space: left-bottom, left-top,
                                  right-top, right-bottom (sm_frustum_corners order) */
    frontend_sort_item *sort;  /* 2 x cap_objects */
    bool truncated;            /* memory ran out growing illum: some sets are cut short */
    /* The unit volume meshes' extents (frontend_init reads them off the meshes): */
    float sphere_vertex_radius;   /* mesh_light_sphere's circumradius (> 1) */
    float cone_rim;               /* the unit cone's largest distance from its axis */
    float cone_apex_z, cone_base_z;   /* its largest and smallest z (apex ~ +1e-4,
                                         base ~ -(1 + 1e-4)) */

    /* >>shadows (see "shadow" above) */
    bool no_shadows;           /* set by the renderer after frontend_init: true = no light
                                  casts shadows (the manifest's `shadows: off`); false (the
                                  zero value) = lights with shadows = true cast them */
    bool no_illumination;      /* set by a renderer that draws no per-light object sets
                                  (all but forward-mpml): illumination sets are computed
                                  only for spots that cast shadows (their shadow-casting
                                  sets are made from them); the others' sets are empty */
    uint32_t nshadowed;        /* lights with a shadow map this frame */
    uint32_t *shadow_layer;    /* per light in `lights`: its layer, or FRONTEND_NO_SHADOW */
    uint32_t *shadow_start;    /* nlights + 1 offsets into shadow */
    uint32_t *shadow;          /* object indices */
    sm_mat4 *shadow_viewproj;  /* per light in `lights` with a layer: world -> light clip */
    size_t cap_shadow;
} frontend;

#define FRONTEND_NO_SHADOW UINT32_MAX

/* Whether light l casts shadows when shadows are on: it asks for them (shadows =
 * true) and is a spot or a directional light. Point lights would need cube maps;
 * seed 000 4.5.6 too implemented shadow mapping "for spot and directional lights". */
bool frontend_light_casts_shadows(const scene_light *l);

bool frontend_init(frontend *f, const scene *s, char *err, size_t errlen);
/* Recomputes everything for the scene as scene_update() last posed it. */
void frontend_build(frontend *f, const scene *s);
void frontend_free(frontend *f);   /* zeroed frontend is fine */

/* The sort key of object i: diffuse map (-1 sorts first), material, mesh:
 *   bits 63..42  diffuse map + 1 (the material's; 0 without one)
 *   bits 41..21  material index
 *   bits 20..0   mesh index
 * (indices beyond the field widths saturate; scenes have far fewer). */
uint64_t frontend_sort_key(const scene *s, uint32_t object);

/* >>light volumes (no GL: scene_gpu uploads and draws what these describe) */

/* The two unit volume meshes as scene_gpu uploads them: mesh_light_sphere(16, 8) and
 * mesh_light_cone(pi/4, 16). Either pointer may be NULL. False with a message (and
 * both zeroed) on failure; mesh_free() releases them. */
bool frontend_volume_meshes(mesh *sphere, mesh *cone, char *err, size_t errlen);

/* The model matrix that places light l's unit volume mesh: point lights
 * T(position) S(1.1 radius); spots T(position) R(-Z onto direction)
 * S(radius tan(angle), radius tan(angle), radius). Directional: identity. */
void frontend_light_volume_model(const scene_light *l, sm_mat4 model);

/* A world-space sphere holding light l's volume mesh as drawn (the mesh's own
 * extents from f). Directional lights: centre 0, radius +INFINITY. */
void frontend_light_volume_bound(const frontend *f, const scene_light *l, sm_vec4 out);

/* The bounding sphere of the cone with apex `apex`, unit axis `dir`, half angle and
 * height (the smallest sphere holding the apex and the base disc). Used for spot
 * light culling with (position, direction, spot_angle, radius). */
void frontend_spot_cone_bound(const sm_vec3 apex, const sm_vec3 dir, float half_angle,
                              float height, sm_vec4 out);
