//VTK::System::Dec
// Strata multi-volume ray caster: the faces of one convex BSP fragment, in the local frame (world
// minus a double-precision origin near the data, so UTM-scale scenes keep their precision).
in vec3 vertexLocal;
uniform mat4 uLocalToClip;

void main()
{
  gl_Position = uLocalToClip * vec4(vertexLocal, 1.0);
}
