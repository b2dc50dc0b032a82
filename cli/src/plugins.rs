//! `tessera plugins [NAME]`: the plugin reference (every plugin a scene file can name, with its
//! parameters' types, defaults, ranges and meanings), or the entries of the plugins called NAME.
use clap::Args;

/// Arguments of `tessera plugins`.
#[derive(Args, Debug, Clone)]
pub struct PluginsArgs {
    /// A plugin name (`roughplastic`, `envmap`, ...); without it, the whole reference.
    pub name: Option<String>,
}

/// Prints the reference; returns the exit code (2 for an unknown name).
pub fn run(args: &PluginsArgs) -> i32 {
    match &args.name {
        None => {
            print!("{}", tessera_scene::reference::reference());
            0
        }
        Some(name) => match tessera_scene::reference::plugin_reference(name) {
            Some(text) => {
                print!("{text}");
                0
            }
            None => {
                eprintln!("error: no plugin is called \"{name}\" (tessera plugins lists them)");
                tessera::InputError::EXIT_CODE
            }
        },
    }
}
