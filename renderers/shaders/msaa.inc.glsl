// The targets a deferred pass reads, multisampled or not (GB_MSAA, renderers/deferred/deferred.c):
// GB_SAMPLER is their sampler type and GB_SAMPLE the sample a texelFetch reads: 0 (per
// pixel: sample 0), gl_SampleID (per-sample shading of edge pixels) or a variable
// (edge_mark.frag, tiled_deferred.comp). Single-sampled, GB_SAMPLE is texelFetch's
// level, 0.
#ifndef GB_SAMPLE
#define GB_SAMPLE 0
#endif
#ifdef GB_MSAA
#define GB_SAMPLER sampler2DMS
#else
#define GB_SAMPLER sampler2D
#endif
