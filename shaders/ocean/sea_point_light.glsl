// The light at one point of the sea at rest (Bruneton, Neyret & Holzschuch 2010, sec. 6: "each
// point is then lit with ... the local Sun elevation"), shared by the projected grid's lighting
// pass (ocean/ocean_lighting.frag) and the view from space (planet/ocean_space.frag), so that the
// two modes light a point identically at the switch. Needs common/frame.glsl and
// atmosphere/sky_provider.glsl.
//
// Frames and units: the nadir frame of common/frame.glsl (m). The atmosphere is the provider's
// sphere of radius atmosphere_radius tangent to the sea at the nadir (centre (0, 0, -R)); the
// point is moved radially onto it for the atmosphere's lookups, which keeps its altitude 0 where
// the planet's quadric and that sphere part (~0.1 km within a surface view's horizon, up to 21 km
// at the limb seen from 36,000 km). Irradiance in W m^-2 nm^-1.
#ifndef THALASSA_OCEAN_SEA_POINT_LIGHT_GLSL
#define THALASSA_OCEAN_SEA_POINT_LIGHT_GLSL

uniform vec3 sun_disc_irradiance;  // L_sun Omega_sun before the atmosphere's transmittance
uniform float atmosphere_radius;   // m, the provider's planet radius
#ifdef SKY_PROVIDER_ENVIRONMENT
// A photograph has no atmosphere and one sky: its irradiance on a horizontal surface (sky only).
uniform vec3 environment_sky_irradiance;
#endif

struct OceanPointLight {
  vec3 ground;          // the point on the atmosphere's sphere (m, nadir frame)
  vec3 camera;          // the camera in the same frame, for the aerial perspective
  vec3 sun_irradiance;  // the sun's irradiance on a surface facing it, at the point (eq. 15)
  vec3 irradiance;      // sun + sky on the sea at rest's tangent plane there (eq. 28's E)
};

// point: a point of the sea at rest (m, nadir frame); up: the sea at rest's unit normal there;
// sun: unit, toward the sun.
OceanPointLight OceanLightAtPoint(vec3 point, vec3 up, vec3 sun) {
  OceanPointLight light;
  const vec3 centre = vec3(0.0, 0.0, -atmosphere_radius);
  light.ground = normalize(point - centre) * atmosphere_radius;
  light.camera = vec3(0.0, 0.0, FrameCameraHeight() + atmosphere_radius);
#ifdef SKY_PROVIDER_ENVIRONMENT
  light.sun_irradiance = sun_disc_irradiance;  // a photograph: no atmosphere
  light.irradiance = sun_disc_irradiance * max(dot(up, sun), 0.0) + environment_sky_irradiance;
#else
  // The sphere's vertical at the point, not the quadric's `up`: the atmosphere's tables are
  // radially symmetric, and the two differ by under 0.2 degrees (the ellipsoid's deflection).
  light.sun_irradiance = sun_disc_irradiance * SkySunTransmittance(light.ground, sun);
  vec3 sky_irradiance;
  light.irradiance =
      SkySunAndSkyIrradiance(light.ground, normalize(light.ground), sun, sky_irradiance) +
      sky_irradiance;
#endif
  return light;
}

#endif  // THALASSA_OCEAN_SEA_POINT_LIGHT_GLSL
