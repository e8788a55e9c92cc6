// The parts of three.js the viewer page uses, bundled by fetch.sh into one minified classic
// script that defines the global `THREE` (works from file://, no modules to resolve).
export {
  WebGLRenderer, Scene, PerspectiveCamera, BufferGeometry, BufferAttribute,
  ShaderMaterial, Mesh, LineSegments, LineBasicMaterial, Vector3, Matrix3, DoubleSide, REVISION
} from 'three';
