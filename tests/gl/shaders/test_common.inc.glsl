// Test include (tests/gl/test_gllayer.c): shared code pulled in by #include.
#ifdef TEST_INCLUDE_ERROR
    this_include_line_is_not_glsl;   // the test checks this line number
#endif

// The pixel's integer coordinates over 255: exact in an 8-bit target below 256.
vec2 test_pixel_coord()
{
    return floor(gl_FragCoord.xy) / 255.0;
}
