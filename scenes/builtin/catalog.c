/* The named scenes manifests can ask for, each with its builder (scene_*.c): the one
 * table of the catalog's scenes. scene_make.c builds them (and file scenes, file_assimp.c). */
#include "scenes/scene.h"

#include <stdlib.h>
#include <string.h>

#include "scenes/scene_build.h"

/* entry first: scene_catalog_at hands out &catalog[i].e */
typedef struct catalog_scene {
    scene_catalog_entry e;
    scene_build_fn build;
    int fault;                 /* test scenes: scene_make.c's inject_fault */
} catalog_scene;

static const catalog_scene catalog[] = {
    {{"empty", "no geometry: an orbiting camera and the run's lights; measures the harness"},
     scene_build_empty, 0},
    {{"shapes", "a floor and a 3 x 3 grid of textured, glossy, normal-mapped and emissive "
               "objects, two of them rotating, under an orbiting camera"},
     scene_build_shapes, 0},
    /* Curtis 2014 (seed 003) section 6 */
    {{"curtis-scene1", "Curtis 2014 scene 1: one rotating model (a torus knot) under a camera "
                      "orbiting once in 60 s; made for 160 lights of radius 10"},
     scene_build_curtis1, 0},
    {{"curtis-scene2", "Curtis 2014 scene 2: two models rotating about the X and Z axes and two "
                      "icospheres, one of which fills the screen from about 19 to 21 s of the "
                      "60 s orbit"},
     scene_build_curtis2, 0},
    {{"curtis-scene3", "Curtis 2014 scene 3: a hundred spheres and four rotating models under "
                      "a 60 s orbit; the scene of the 0 to 590 light growth"},
     scene_build_curtis3, 0},
    /* seed 000 section 4.8 */
    {{"canyon", "seed 000's exterior: four 128 x 128-cell terrain tiles forming an 8192-unit "
               "canyon, a sun (its authored light), ambient and sky, draw distance 8192, an "
               "orbit over the valley that sees to the far plane"},
     scene_build_canyon, 0},
    {{"interior", "seed 000's interior: a dark generator hall and corridor of 72 mesh "
                 "instances, draw distance 2048; authored lights: a shadowing moon, 5 omni "
                 "lights, 3 shadowing spots overlapping between the two generators"},
     scene_build_interior, 0},
    /* seed 000 sections 5.4 and 5.5: scripted cameras, camera.hold 0 and 1 are the two ends */
    {{"spot-coverage", "seed 000 5.4.1: one spot light covering about half the screen (hold 0), "
                      "then the camera inside its cone (hold 1)"},
     scene_build_spot_coverage, 0},
    {{"two-spots-overlap", "seed 000 5.4.2: two overlapping spots seen from above, zooming from "
                          "a small overlap (hold 0) until it fills the screen (hold 1)"},
     scene_build_two_spots, 0},
    {{"floating-spot", "seed 000 5.5: a spot whose volume covers most of the screen (hold 1) "
                      "while it lights no visible pixel"},
     scene_build_floating_spot, 0},
    /* ours: the translucent pass (renderers/frame/translucent.h) */
    {{"glass", "four overlapping translucent panes of different colours and 24 translucent "
              "particles over a textured floor, 12 authored point lights, a 30 s orbit"},
     scene_build_glass, 0},
};

/* Scenes that fail on purpose at schedule time 0.2 s, for the tests of run
 * isolation; they exist only where SHADESWEEP_TEST_SCENES=1. */
static const catalog_scene test_catalog[] = {
    {{"test-abort", "calls abort()"},
     scene_build_empty, 1},
    {{"test-segv", "raises SIGSEGV"},
     scene_build_empty, 2},
    {{"test-sigkill", "raises SIGKILL, as a kill -9 from outside would"},
     scene_build_empty, 3},
    {{"test-hang", "never returns"},
     scene_build_empty, 4},
};

static bool test_scenes_enabled(void)
{
    const char *v = getenv("SHADESWEEP_TEST_SCENES");
    return v && strcmp(v, "1") == 0;
}

size_t scene_catalog_count(void)
{
    return sizeof catalog / sizeof catalog[0] +
           (test_scenes_enabled() ? sizeof test_catalog / sizeof test_catalog[0] : 0);
}

const scene_catalog_entry *scene_catalog_at(size_t i)
{
    size_t n = sizeof catalog / sizeof catalog[0];
    if (i < n)
        return &catalog[i].e;
    return i < scene_catalog_count() ? &test_catalog[i - n].e : NULL;
}

scene_build_fn scene_catalog_builder(const scene_catalog_entry *e)
{
    return e ? ((const catalog_scene *)e)->build : NULL;
}

int scene_catalog_fault(const scene_catalog_entry *e)
{
    return e ? ((const catalog_scene *)e)->fault : 0;
}

const scene_catalog_entry *scene_catalog_find(const char *name)
{
    for (size_t i = 0; i < scene_catalog_count(); i++)
        if (strcmp(scene_catalog_at(i)->name, name) == 0)
            return scene_catalog_at(i);
    return NULL;
}
