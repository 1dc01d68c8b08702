//! (to be written) csl reader and writer. API: read_csl(path) / parse_csl(text, file_name) -> Result<Sections>,
//! write_csl(path, &Sections) -> Result<()>, to_csl_string(&Sections) -> String.
