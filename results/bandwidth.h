#pragma once
/* Seed 002's memory-traffic model of deferred shading (Thibieroz, ShaderX2, section "MRT
 * Configuration and Bandwidth": Table 1's variables, equations 4-7, Table 2). Arithmetic
 * only, no GL.
 *
 * Units (bytes, as the paper's worked example) and what the project measures with it:
 * the comment above s002_vars below. */

/* Units: every size is in BYTES per pixel or per texel. Table 1 states bit depths
 * (32 bpp, 24 bpp), but the paper's own worked example puts them in as bytes (32 bpp as
 * 4, 24 bpp as 3), and so does Table 2; so do we. The one oddity of that example, its
 * depth/stencil term written as 8 x (Overdraw + Sorting) although Z_BPP is 32 bpp, is
 * reproduced by passing z_bytes = 8 (the test does; read it as a read and a write of a
 * 32-bit depth).
 *
 * What the project measures with it (renderers/deferred/gbuffer_layout.h, deferred_gbuffer_traffic):
 * only the MRT terms, the bytes the G-buffer pass writes (equation 4's
 * n_MRT x W x H x MRT_BPP x Sorting) and the light passes read (equation 5's
 * n_MRT x W x H x MRT_BPP x n), with the pixel counts the paper estimates (W x H x
 * Sorting, W x H x n) replaced by the ones the run counts (GL_SAMPLES_PASSED of those
 * passes), and n_MRT x MRT_BPP by the sum of the layout's attachments' bytes per pixel
 * (the paper's optimised 96-bit layout already mixes bit depths). */
typedef struct s002_vars {
    double w, h;               /* W, H: render width and height, pixels */
    double z_bytes;            /* Z_BPP: depth/stencil bytes per pixel */
    double bb_bytes;           /* BB_BPP: back buffer bytes per pixel */
    double overdraw;           /* Overdraw: average overdraw per pixel */
    double sorting;            /* Sorting: average pixels drawn back to front, 1..Overdraw */
    double t_bytes;            /* T_BPP: average texture bytes per texel */
    double t_building;         /* T_B: texture lookups per pixel, building pass */
    double t_shading;          /* T_S: texture lookups per pixel, shading pass */
    double n;                  /* n: shading passes (full screen) */
    double n_mrt;              /* n_MRT: render targets, 1..4 */
    double mrt_bytes;          /* MRT_BPP: bytes per pixel of one target */
    double c_geometry;         /* C_Geometry: vertex and index buffers, bytes per frame */
} s002_vars;

/* Equation 4, the building (G-buffer) pass, bytes per frame:
 *   W H [Z_BPP (Overdraw + Sorting) + T_BPP T_B Sorting + n_MRT MRT_BPP Sorting] + C_Geometry */
double s002_building_bytes(const s002_vars *v);

/* Equation 5, the n shading passes, bytes per frame:
 *   W H n [2 BB_BPP + T_S T_BPP + n_MRT MRT_BPP] */
double s002_shading_bytes(const s002_vars *v);

/* Equation 6: (equation 4 + equation 5) x fps, bytes per second; the paper takes 60 fps. */
double s002_bandwidth(const s002_vars *v, double fps);

/* Equation 7, the paper's gross approximation of equation 6 at Table 1's values and 60 fps:
 *   n_MRT x MRT_BPP / 2 + 10, in GB/s with MRT_BPP in bytes (what Table 2 lists). */
double s002_bandwidth_approx_gbps(double n_mrt, double mrt_bytes);

/* Equation 4's MRT term: bytes_per_pixel (n_MRT x MRT_BPP, or the sum over targets of
 * mixed depths) x the samples the building pass writes (W x H x Sorting). */
double s002_mrt_write_bytes(double bytes_per_pixel, double written_samples);

/* Equation 5's MRT term: bytes_per_pixel x the samples the shading passes shade, every
 * one reading every target (W x H x n). */
double s002_mrt_read_bytes(double bytes_per_pixel, double shaded_samples);

/* One frame's G-buffer traffic by those two terms; NAN where there is no G-buffer or a
 * count is unavailable. */
typedef struct gbuffer_traffic {
    double write_bytes;        /* the G-buffer pass's writes (equation 4's MRT term) */
    double read_bytes;         /* the light passes' reads (equation 5's MRT term) */
} gbuffer_traffic;
