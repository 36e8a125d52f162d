// `shadesweep probe`'s memory bandwidth: a buffer copied into another, one vec4 an
// invocation (the copy reads and writes every byte once).
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Src { vec4 src[]; };
layout(std430, binding = 1) writeonly buffer Dst { vec4 dst[]; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    dst[i] = src[i];
}
