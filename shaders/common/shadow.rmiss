#version 460
// Shadow miss shader (chapter 06): the shadow ray reached the light.
#extension GL_EXT_ray_tracing : require

layout(location = 1) rayPayloadInEXT uint shadowed;

void main() { shadowed = 0u; }
