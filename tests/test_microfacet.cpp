// Chapter 15's microfacet model (shaders/common/microfacet.glsl), compiled
// as C++ and checked as PBRT-v4 and Mitsuba check theirs:
// - the distribution is normalized (the projected microfacet area is the
//   macro-surface's), and so is the density of visible normals;
// - sampling matches evaluation: directions drawn as the ray tree draws
//   them (a visible normal, then reflection or refraction about it, chosen
//   by Fresnel) fall into bins of the sphere as often as the evaluated
//   density integrated over each bin says (a chi-square test), and each
//   branch's share equals the BSDF times cos over that density;
// - reflection is reciprocal, transmission reciprocal up to n^2;
// - energy: the white furnace in one bounce (the light scattered from a
//   uniform sky) is 1 at alpha -> 0 and falls with alpha, never above 1;
//   the loss of single scattering is printed (chapter 15's page);
// - the albedo table the build computes from the visible normals' shares
//   (tools/microfacet_albedo.cpp) is the BSDF integrated over directions,
//   and compensated by it one bounce keeps all the light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "glsl_as_cpp.h"
#include "scene/microfacet_albedo.h"

namespace shader {
#define ALBEDO_TABLE(i) rg::kMicrofacetAlbedo[i]
#include "albedo_table.glsl"
#undef ALBEDO_TABLE
}  // namespace shader

namespace {

using glm::vec2;
using glm::vec3;
constexpr double kPi = 3.14159265358979323846;

vec3 fromAngles(double theta, double phi) {
    return vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                float(std::cos(theta)));
}

// The integral of f over the sphere (or the upper hemisphere), in theta and
// phi by the midpoint rule, fine enough for the lobes tested here.
template <class F>
double integrate(F f, double thetaMax = kPi, int steps = 800) {
    double sum = 0, dt = thetaMax / steps, dp = 2 * kPi / (2 * steps);
    for (int i = 0; i < steps; ++i) {
        double theta = (i + 0.5) * dt;
        for (int j = 0; j < 2 * steps; ++j)
            sum += f(fromAngles(theta, (j + 0.5) * dp)) * std::sin(theta) * dt * dp;
    }
    return sum;
}

TEST(Microfacet, DistributionIsNormalized) {
    for (float alpha : {0.1f, 0.3f, 0.6f, 1.0f}) {
        double area = integrate([&](vec3 m) { return shader::ggxD(m, alpha) * m.z; }, kPi / 2, 1200);
        EXPECT_NEAR(area, 1.0, 2e-3) << "alpha " << alpha;
    }
}

TEST(Microfacet, VisibleNormalsAreNormalizedAndSampledWithTheirDensity) {
    for (float alpha : {0.2f, 0.6f, 1.0f})
        for (double thetaO : {0.0, 0.7, 1.4}) {
            vec3 wo = fromAngles(thetaO, 0.3);
            double total = integrate([&](vec3 m) { return shader::visibleNormalPdf(wo, m, alpha); },
                                     kPi / 2, 1000);
            EXPECT_NEAR(total, 1.0, 3e-3) << "alpha " << alpha << ", theta " << thetaO;
            // the mean of m.z over samples against the density's
            double expected = integrate(
                [&](vec3 m) { return shader::visibleNormalPdf(wo, m, alpha) * m.z; }, kPi / 2, 1000);
            std::mt19937 rng(7);
            std::uniform_real_distribution<float> u(0, 1);
            double sum = 0;
            const int n = 200000;
            for (int k = 0; k < n; ++k) sum += shader::sampleVisibleNormal(wo, alpha, vec2(u(rng), u(rng))).z;
            EXPECT_NEAR(sum / n, expected, 3e-3) << "alpha " << alpha << ", theta " << thetaO;
        }
}

// Q(a, x), the regularized upper incomplete gamma function: the chi-square
// test's p-value is Q(dof / 2, chi2 / 2) (Numerical Recipes' series and
// continued fraction).
double gammaQ(double a, double x) {
    if (x <= 0) return 1;
    double lg = std::lgamma(a);
    if (x < a + 1) {
        double term = 1 / a, sum = term;
        for (int n = 1; n < 1000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::abs(term) < std::abs(sum) * 1e-15) break;
        }
        return 1 - sum * std::exp(-x + a * std::log(x) - lg);
    }
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
    for (int i = 1; i < 1000; ++i) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::abs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - lg) * h;
}

struct Case {
    float alpha, n1, n2;
    double thetaO;
};

// One direction drawn as the ray tree draws it, with the probability the
// tree's two branches stand for: reflection with probability F at the
// sampled normal, refraction otherwise. Returns false where the direction
// falls on the wrong side (the light single scattering loses).
bool sampleDirection(const Case& c, vec3 wo, vec2 u, float choice, vec3& wi) {
    vec3 m = shader::sampleVisibleNormal(wo, c.alpha, u);
    float F = shader::fresnel(FRESNEL_EXACT, 0, glm::dot(wo, m), c.n1, c.n2);
    shader::MicrofacetSplit s = shader::microfacetSplit(wo, m, c.alpha, c.n1, c.n2, FRESNEL_EXACT, 0);
    if (choice < F) {
        wi = s.reflected;
        return wi.z > 0;
    }
    wi = s.refracted;
    return wi.z < 0;
}

// The density of sampleDirection's directions: F at the reflection's
// normal times the reflection's density, (1 - F) at the refraction's times
// the refraction's.
double sampledDensity(const Case& c, vec3 wo, vec3 wi) {
    vec3 m = wi.z > 0 ? wo + wi : -(c.n1 * wo + c.n2 * wi);
    if (glm::dot(m, m) == 0) return 0;
    m = glm::normalize(m);
    if (m.z < 0) m = -m;
    float F = shader::fresnel(FRESNEL_EXACT, 0, glm::dot(wo, m), c.n1, c.n2);
    return (wi.z > 0 ? F : 1 - F) * shader::dielectricPdf(wo, wi, c.alpha, c.n1, c.n2);
}

TEST(Microfacet, SamplingMatchesTheDensityChiSquare) {
    std::vector<Case> cases;
    for (float alpha : {0.1f, 0.4f, 1.0f})
        for (float n : {1.33f, 1.5f, 2.4f})
            for (double theta : {0.2, 1.0, 1.45}) {
                cases.push_back({alpha, 1.0f, n, theta});  // entering
                if (n == 1.5f) cases.push_back({alpha, n, 1.0f, theta});  // leaving: total reflection
            }
    const int thetaBins = 40, phiBins = 40, samples = 400000;
    // Sidak's correction: every case at 1 % together
    const double significance = 1 - std::pow(1 - 0.01, 1.0 / double(cases.size()));
    for (const Case& c : cases) {
        vec3 wo = fromAngles(c.thetaO, 0);
        std::vector<double> observed(thetaBins * phiBins, 0), expected(thetaBins * phiBins, 0);
        std::mt19937 rng(1234);
        std::uniform_real_distribution<float> u(0, 1);
        for (int k = 0; k < samples; ++k) {
            vec3 wi;
            if (!sampleDirection(c, wo, vec2(u(rng), u(rng)), u(rng), wi)) continue;
            double theta = std::acos(std::clamp(double(wi.z), -1.0, 1.0));
            double phi = std::atan2(double(wi.y), double(wi.x));
            if (phi < 0) phi += 2 * kPi;
            int i = std::min(thetaBins - 1, int(theta / kPi * thetaBins));
            int j = std::min(phiBins - 1, int(phi / (2 * kPi) * phiBins));
            observed[i * phiBins + j] += 1;
        }
        // each bin's expected count: the density integrated over it
        const int sub = 24;
        for (int i = 0; i < thetaBins; ++i)
            for (int j = 0; j < phiBins; ++j) {
                double t0 = i * kPi / thetaBins, p0 = j * 2 * kPi / phiBins;
                double dt = kPi / thetaBins / sub, dp = 2 * kPi / phiBins / sub, sum = 0;
                for (int a = 0; a < sub; ++a)
                    for (int b = 0; b < sub; ++b) {
                        double theta = t0 + (a + 0.5) * dt;
                        sum += sampledDensity(c, wo, fromAngles(theta, p0 + (b + 0.5) * dp)) *
                               std::sin(theta) * dt * dp;
                    }
                expected[i * phiBins + j] = sum * samples;
            }
        // Bins expecting fewer than 5 are pooled into one (as PBRT-v4 does).
        double chi2 = 0, pooledObserved = 0, pooledExpected = 0;
        int dof = -1;
        for (size_t k = 0; k < observed.size(); ++k) {
            if (expected[k] < 5) {
                pooledObserved += observed[k], pooledExpected += expected[k];
                continue;
            }
            chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
            ++dof;
        }
        if (pooledExpected >= 5) {
            chi2 += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
            ++dof;
        } else {
            EXPECT_LT(pooledObserved, 5 + 5 * pooledExpected) << "samples where the density says none";
        }
        double p = gammaQ(dof / 2.0, chi2 / 2);
        EXPECT_GT(p, significance) << "alpha " << c.alpha << ", n " << c.n1 << " -> " << c.n2 << ", theta "
                                   << c.thetaO << ": chi2 " << chi2 << " over " << dof << " degrees of freedom";
    }
}

TEST(Microfacet, EachBranchCarriesTheBsdfOverItsDensity) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(0, 1);
    int checked = 0;
    for (float alpha : {0.05f, 0.3f, 0.8f})
        for (float n2 : {1.33f, 1.5f, 2.4f})
            for (bool leaving : {false, true})
                for (int k = 0; k < 2000; ++k) {
                    float n1 = leaving ? n2 : 1.0f, n = leaving ? 1.0f : n2;
                    vec3 wo = fromAngles(1.5 * u(rng), 6.28 * u(rng));
                    vec3 m = shader::sampleVisibleNormal(wo, alpha, vec2(u(rng), u(rng)));
                    shader::MicrofacetSplit s = shader::microfacetSplit(wo, m, alpha, n1, n, FRESNEL_EXACT, 0);
                    auto check = [&](vec3 wi, float share) {
                        float pdf = shader::dielectricPdf(wo, wi, alpha, n1, n);
                        if (share <= 0 || pdf < 1e-3f) return;
                        float F = shader::fresnel(FRESNEL_EXACT, 0, glm::dot(wo, m), n1, n);
                        // the share stands for one branch: its density is the normal's,
                        // without the choice's F or 1 - F
                        float value = shader::dielectricCosBsdf(wo, wi, alpha, n1, n, FRESNEL_EXACT, 0) / pdf;
                        EXPECT_NEAR(value, share, 2e-3f * std::max(1.0f, share))
                            << "alpha " << alpha << ", " << n1 << " -> " << n << ", F " << F;
                        ++checked;
                    };
                    check(s.reflected, s.reflectedShare);
                    check(s.refracted, s.refractedShare);
                    EXPECT_LE(s.reflectedShare + s.refractedShare, 1.0f + 1e-5f);
                }
    EXPECT_GT(checked, 30000);
}

TEST(Microfacet, ReflectionIsReciprocalTransmissionUpToTheIndicesSquared) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0, 1);
    for (int k = 0; k < 5000; ++k) {
        float alpha = 0.05f + u(rng), n = 1.2f + u(rng);
        vec3 a = fromAngles(1.5 * u(rng), 6.28 * u(rng)), b = fromAngles(1.5 * u(rng), 6.28 * u(rng));
        // f(a, b) = f(b, a): the value over |wi.z|
        float fab = shader::dielectricCosBsdf(a, b, alpha, 1, n, FRESNEL_EXACT, 0) / b.z;
        float fba = shader::dielectricCosBsdf(b, a, alpha, 1, n, FRESNEL_EXACT, 0) / a.z;
        EXPECT_NEAR(fab, fba, 1e-4f * std::max(1.0f, fab));
        // through the surface: a above in index 1, b below in index n; seen from
        // below the frame turns over (z -> -z) and the indices swap
        vec3 below(b.x, b.y, -b.z), flippedA(a.x, a.y, -a.z);
        float t1 = shader::dielectricCosBsdf(a, below, alpha, 1, n, FRESNEL_EXACT, 0) / b.z;
        float t2 = shader::dielectricCosBsdf(b, flippedA, alpha, n, 1, FRESNEL_EXACT, 0) / a.z;
        // radiance not rescaled: f_t(a -> b) / n^2 = f_t(b -> a) / 1^2 (Veach 1997, 5.2)
        EXPECT_NEAR(t1 / (n * n), t2, 2e-4f * std::max(1.0f, t2)) << "alpha " << alpha << ", n " << n;
    }
}

// The white furnace in one bounce: light from a uniform white sky scattered
// towards wo, the sum of both branches' shares over visible normals (their
// mean is the integral of the BSDF times cos). 1 where nothing is lost.
double albedo(float alpha, float n1, float n2, double thetaO, int samples = 40000) {
    vec3 wo = fromAngles(thetaO, 0);
    double sum = 0;
    int side = int(std::sqrt(double(samples)));
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j) {
            vec3 m = shader::sampleVisibleNormal(wo, alpha, vec2((i + 0.5f) / side, (j + 0.5f) / side));
            shader::MicrofacetSplit s = shader::microfacetSplit(wo, m, alpha, n1, n2, FRESNEL_EXACT, 0);
            sum += s.reflectedShare + s.refractedShare;
        }
    return sum / (double(side) * side);
}

TEST(Microfacet, OneBounceFurnaceLosesEnergyWithRoughnessNeverGains) {
    std::printf("single scattering's albedo (n = 1.5): alpha, entering at 0/60/80 deg, leaving at 0/30 deg\n");
    double last = 1;
    for (float alpha : {0.001f, 0.1f, 0.3f, 0.5f, 0.8f, 1.0f}) {
        double e0 = albedo(alpha, 1, 1.5f, 0), e60 = albedo(alpha, 1, 1.5f, 1.047), e80 = albedo(alpha, 1, 1.5f, 1.396);
        double l0 = albedo(alpha, 1.5f, 1, 0), l30 = albedo(alpha, 1.5f, 1, 0.524);
        std::printf("  %.3f: %.4f %.4f %.4f | %.4f %.4f\n", alpha, e0, e60, e80, l0, l30);
        for (double e : {e0, e60, e80, l0, l30}) EXPECT_LE(e, 1.0 + 1e-4);
        if (alpha < 0.01f) {  // smooth: nothing lost
            EXPECT_NEAR(e0, 1.0, 1e-4);
            EXPECT_NEAR(e80, 1.0, 1e-4);
        }
        EXPECT_LE(e60, last + 1e-4) << "the loss grows with alpha";
        last = e60;
    }
    // page 15: at alpha = 1 one surface keeps about three quarters entering
    // glass at 60 degrees, under half leaving it
    EXPECT_NEAR(albedo(1.0f, 1, 1.5f, 1.047), 0.75, 0.05);
    EXPECT_LT(albedo(1.0f, 1.5f, 1, 0), 0.5);
    EXPECT_LT(albedo(1.0f, 1.5f, 1, 0.524), 0.5);
}

// Page 15's --sampling cone (sampleConeMixture): chapter 11's cone alone
// carries the lobe times cos times the cone's solid angle, a hundred times
// its share and more where a direction finds the lobe's peak; mixed half and
// half with visible normals, every share is at most twice a visible
// normal's (at most 2 here, no compensation) and the mean is the same
// albedo: nothing outside the cone is lost any more.
TEST(Microfacet, ConeMixtureKeepsTheAlbedoAndBoundsEveryShare) {
    std::printf("cone mixture: roughness, n1 -> n2, theta_o: albedo (visible normals, mixture), "
                "largest share (mixture, the cone alone)\n");
    const int side = 400;
    double worstAlone = 0;
    for (float roughness : {0.05f, 0.15f, 0.4f, 0.8f})
        for (auto [n1, n2] : {std::pair{1.0f, 1.5f}, std::pair{1.5f, 1.0f}, std::pair{1.0f, 2.4f}})
            for (double thetaO : {0.0, 0.7, 1.3}) {
                float alpha = roughness * roughness;
                vec3 wo = fromAngles(thetaO, 0.3);
                double sum = 0, largest = 0, alone = 0;
                float cosMax = std::cos(roughness * 0.5f * float(kPi));
                for (int i = 0; i < side; ++i)
                    for (int j = 0; j < side; ++j) {
                        vec2 u((i + 0.5f) / side, (j + 0.5f) / side);
                        shader::ConeMixtureSample c = shader::sampleConeMixture(wo, alpha, n1, n2, u);
                        for (auto [wi, density] : {std::pair{c.reflected, c.reflectedDensity},
                                                   std::pair{c.refracted, c.refractedDensity}}) {
                            if (density <= 0) continue;
                            double f = shader::dielectricCosBsdf(wo, wi, alpha, n1, n2, FRESNEL_EXACT, 0);
                            double share = f / density;
                            sum += share, largest = std::max(largest, share);
                            // the same direction with the cone's density alone (its half of the samples)
                            vec3 axis = wi.z > 0 ? vec3(-wo.x, -wo.y, wo.z) : glm::refract(-wo, vec3(0, 0, 1), n1 / n2);
                            float cone = shader::coneDensity(axis, wi, cosMax);
                            if (u.x < 0.5f && cone > 0) alone = std::max(alone, f / cone);
                        }
                    }
                double mean = sum / (double(side) * side), expected = albedo(alpha, n1, n2, thetaO);
                std::printf("  %.2f %.1f -> %.1f %.1f: %.4f %.4f, %.3f %.1f\n", roughness, n1, n2, thetaO, expected,
                            mean, largest, alone);
                EXPECT_NEAR(mean, expected, 0.01) << "roughness " << roughness << ", " << n1 << " -> " << n2
                                                  << ", theta " << thetaO;
                EXPECT_LE(largest, 2.0 + 1e-3) << "roughness " << roughness << ", " << n1 << " -> " << n2;
                worstAlone = std::max(worstAlone, alone);
            }
    EXPECT_GT(worstAlone, 100.0) << "the cone alone";
}

// [region albedo_table]
// The table's nodes against the BSDF integrated over the sphere of
// directions (the evaluation, not the sampling the table was made with),
// for a dielectric entered and left and for a mirror (F = 1: D G2 / (4 cos_o)).
TEST(Microfacet, AlbedoTableIsTheIntegralOfTheBsdf) {
    double worst = 0;
    // eta 1.52 and 3 entered, their inverses left, and the mirror
    for (uint32_t slice : {ALBEDO_ETA / 4u, ALBEDO_ETA - 1u, ALBEDO_ETA + ALBEDO_ETA / 4u, 2u * ALBEDO_ETA - 1u,
                           ALBEDO_MIRROR_SLICE})
        for (uint32_t r : {9u, 16u, 31u})
            for (uint32_t c : {8u, 20u, 31u}) {
                float cosO = float(c) / (ALBEDO_COS - 1), roughness = float(r) / (ALBEDO_ROUGH - 1);
                float alpha = roughness * roughness, eta = rg::gpu::albedoSliceEta(slice);
                vec3 wo(std::sqrt(1 - cosO * cosO), 0, cosO);
                // the midpoint rule needs finer steps for the narrower lobe
                double integral = integrate([&](vec3 wi) -> double {
                    if (slice != ALBEDO_MIRROR_SLICE)
                        return shader::dielectricCosBsdf(wo, wi, alpha, 1, eta, FRESNEL_EXACT, 0);
                    if (wi.z <= 0) return 0;
                    return shader::ggxD(glm::normalize(wo + wi), alpha) * shader::smithG2(wo, wi, alpha) /
                           (4 * wo.z);
                }, kPi, r < 10 ? 1600 : 1200);
                double table = rg::kMicrofacetAlbedo[(slice * ALBEDO_ROUGH + r) * ALBEDO_COS + c];
                worst = std::max(worst, std::abs(table - integral));
                EXPECT_NEAR(table, integral, 2e-3)
                    << "slice " << slice << " (eta " << eta << "), roughness " << roughness << ", cos " << cosO;
                EXPECT_LE(table, 1 + 1e-4);
            }
    std::printf("albedo table against the integrated BSDF: largest difference %.5f\n", worst);
    // roughness 0 keeps everything
    for (uint32_t slice = 0; slice < ALBEDO_SLICES; ++slice)
        EXPECT_NEAR(rg::kMicrofacetAlbedo[slice * ALBEDO_ROUGH * ALBEDO_COS + ALBEDO_COS - 1], 1.0, 1e-5);
}

// Between the nodes (albedo_table.glsl's interpolation) the table still
// gives the albedo, and the compensated bounce keeps 1 within 1 %.
TEST(Microfacet, CompensatedBounceKeepsAllTheLight) {
    double worst = 0;
    for (auto [n1, n2] : {std::pair{1.0f, 1.5f}, {1.5f, 1.0f}, {1.0f, 1.33f}, {1.0f, 2.4f}, {1.33f, 1.5f}})
        for (float roughness : {0.25f, 0.45f, 0.7f, 0.95f, 1.0f})
            for (double theta : {0.1, 0.7, 1.2}) {
                double e = albedo(roughness * roughness, n1, n2, theta);
                double table = shader::dielectricAlbedo(float(std::cos(theta)), roughness, n1, n2);
                worst = std::max(worst, std::abs(e / table - 1));
                EXPECT_NEAR(e / table, 1.0, 0.01)
                    << "n " << n1 << " -> " << n2 << ", roughness " << roughness << ", theta " << theta;
            }
    std::printf("compensated bounce between the nodes: largest error %.2f %%\n", 100 * worst);
}
// [end]

TEST(Microfacet, SmoothLimitIsTheMirrorAndSnell) {
    vec3 wo = fromAngles(0.6, 0.2);
    vec3 m = shader::sampleVisibleNormal(wo, 1e-4f, vec2(0.3f, 0.8f));
    EXPECT_NEAR(m.z, 1.0f, 1e-6f);
    shader::MicrofacetSplit s = shader::microfacetSplit(wo, m, 1e-4f, 1, 1.5f, FRESNEL_EXACT, 0);
    float F = shader::fresnelExact(wo.z, 1, 1.5f);
    EXPECT_NEAR(s.reflectedShare, F, 1e-5f);
    EXPECT_NEAR(s.refractedShare, 1 - F, 1e-5f);
    EXPECT_NEAR(s.reflected.z, wo.z, 1e-4f);
    // Snell: sin t = sin i / 1.5
    float sinT = std::sqrt(s.refracted.x * s.refracted.x + s.refracted.y * s.refracted.y);
    EXPECT_NEAR(sinT, std::sin(0.6f) / 1.5f, 1e-4f);
}

}  // namespace
