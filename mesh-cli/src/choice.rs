//! The one way the command line turns a name into a library enum: clap's
//! `PossibleValuesParser` over the enum's own list of names (so `--help`
//! lists them and a wrong name is refused with the list), then the enum's
//! `FromStr`. Every selectable enum of the workspace has `ALL` and `name()`,
//! so a flag reads
//! `#[arg(long, default_value_t = X::default(), value_parser = choice::<X>(X::ALL.map(X::name)))]`.

use std::str::FromStr;

use clap::builder::{PossibleValuesParser, TypedValueParser};

/// A clap value parser for `T` that accepts exactly `names` (the enum's list,
/// `T::ALL.map(T::name)`) and parses them with `T::from_str`. O(names).
pub(crate) fn choice<T>(names: impl IntoIterator<Item = &'static str>) -> impl TypedValueParser<Value = T>
where
    T: FromStr + Clone + Send + Sync + 'static,
    T::Err: Into<Box<dyn std::error::Error + Send + Sync + 'static>>,
{
    PossibleValuesParser::new(names).try_map(|s| s.parse::<T>())
}
