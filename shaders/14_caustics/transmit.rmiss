#version 460
// Chapter 14's --caustics transmit: a shadow ray that reached the light
// keeps what the glass on its way let through (transmit.glsl).
#extension GL_EXT_ray_tracing : require

layout(location = 2) rayPayloadInEXT vec4 transmittance;

void main() {}
