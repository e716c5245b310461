//! Weighted perfect matching on sparse graphs (primal-dual blossom algorithm).
//! (Filled in by the matching work.)
