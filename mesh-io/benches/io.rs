//! Read and write throughput of every format (filled in below).

fn main() {}
