//VTK::System::Dec
// Strata stacked height-field ray caster: proxy box vertex shader. The box is drawn with its
// back faces (depth clamped), so every pixel whose ray can meet the stack gets one fragment,
// wherever the camera is, inside the box included.
in vec3 vertexGrid;
uniform mat4 uGridToClip;
void main()
{
  gl_Position = uGridToClip * vec4(vertexGrid, 1.0);
}
