//! Meshes of known shape and topology (spheres, tori, multi-tori, disks with holes) for tests and the demo. TODO(helper).
