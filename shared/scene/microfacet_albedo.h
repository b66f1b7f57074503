// Chapter 15's albedo table (host_device.h's ALBEDO_*): how much light a
// rough dielectric or mirror keeps after one microfacet scattering,
// computed at build time by tools/microfacet_albedo.cpp. The chapter
// uploads it for the shaders (albedo_table.glsl); the reference reads it.
#pragma once
#include "host_device.h"

namespace rg {
extern const float kMicrofacetAlbedo[ALBEDO_ENTRIES];
}
