//! Level-of-detail strips: multiresolution strips with sorted edges (SETS) and LoD
//! strips for deforming meshes.
