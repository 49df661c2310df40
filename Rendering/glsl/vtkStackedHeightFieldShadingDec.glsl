// Lighting like any VTK surface: the actor's vtkProperty and the renderer's lights.
uniform mat3 uNormalMatrix; // grid -> view, inverse transpose
uniform mat4 uGridToView;
uniform int uParallel;
uniform float uAmbient, uDiffuse, uSpecular, uSpecularPower;
uniform vec3 uSpecularColor;
//STRATA::LightingUniforms::Dec
