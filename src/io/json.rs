//! (to be written) json reader and writer. API: read_json(path) / parse_json(text, file_name) -> Result<Sections>,
//! write_json(path, &Sections) -> Result<()>, to_json_string(&Sections) -> String.
