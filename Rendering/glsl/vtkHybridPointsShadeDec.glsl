// Shaded points: two-sided Blinn-Phong with the scene's directional lights, as the ray caster
// shades.
in vec3 pointNormal;
uniform mat3 uNormalToWorld;
uniform vec4 uMaterial; // ambient, diffuse, specular, specular power
uniform int uNumLights;
uniform vec3 uLightDirection[8];
uniform vec3 uLightColor[8];
uniform vec3 uViewDirection; // towards the eye
