// What a deferred light pass writes (deferred_ambient.frag starts it, deferred_light.frag
// adds to it): the light target, and with SEPARATE_SPECULAR (seed 001) the specular target
// beside it, summed by deferred_compose.frag.
layout(location = 0) out vec4 o_light;
#ifdef SEPARATE_SPECULAR
layout(location = 1) out vec4 o_specular;
#endif
