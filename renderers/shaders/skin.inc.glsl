// Skinning (SKINNING: a common define for a scene with skins, scenes/scene_anim.h): a
// vertex's matrix is the weighted sum of its joints' matrices from the frame's joint
// palette, a texture buffer of RGBA32F texels, a matrix's 4 columns each (scene_gpu.c,
// bound to BIND_TEX_JOINTS by scene_gpu_frame). mesh.vert (every pass that draws a scene
// mesh), shadow.vert and visibility_shade.comp (its refetched triangles) all call
// skin_matrix, so every pass skins alike. Weights of 0 (the generic value of a mesh
// without a skin) give the identity. Joints are in range and weights finite, summing to
// 1, for a skinned mesh (file_skin.c checks the file's). Normals and tangents take the
// matrix's upper 3x3 (exact for rotations and uniform scales, as glTF viewers do; the
// shaders normalise after).
// (bindings.h first: the loader includes a file once, #ifdef or not)
#include "bindings.h"

layout(binding = BIND_TEX_JOINTS) uniform samplerBuffer t_joints;

mat4 skin_joint(uint j)
{
    int b = int(j) * 4;
    return mat4(texelFetch(t_joints, b), texelFetch(t_joints, b + 1),
                texelFetch(t_joints, b + 2), texelFetch(t_joints, b + 3));
}

mat4 skin_matrix(uvec4 joints, vec4 weights)
{
    if (weights == vec4(0.0))
        return mat4(1.0);
    return weights.x * skin_joint(joints.x) + weights.y * skin_joint(joints.y) +
           weights.z * skin_joint(joints.z) + weights.w * skin_joint(joints.w);
}
