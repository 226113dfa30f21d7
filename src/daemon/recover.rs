//! `impactd recover`: salvages a recording cut off by a crash into a new, complete MCAP file.

use std::collections::HashMap;
use std::path::Path;

use super::replay::{is_mcap, mcap_err, read_file};
use super::DaemonError;

/// What `recover` salvaged.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Recovered {
    pub messages: u64,
    /// The input was complete: nothing was lost.
    pub complete: bool,
}

/// Copies every readable message and metadata record of `input` into a new, complete MCAP file.
pub fn recover(input: &Path, output: &Path) -> Result<Recovered, DaemonError> {
    let bytes = read_file(input)?;
    if !is_mcap(&bytes) {
        return Err(DaemonError::NotMcap { path: input.display().to_string() });
    }
    let file = std::fs::File::create(output)
        .map_err(|e| DaemonError::Io { what: format!("creating {}", output.display()), source: e })?;
    let mut w = mcap::WriteOptions::new()
        .compression(Some(mcap::Compression::Zstd))
        .profile("")
        .create(std::io::BufWriter::new(file))
        .map_err(|e| mcap_err(output, e))?;
    let mut complete = mcap::read::footer(&bytes).is_ok();
    for record in mcap::read::LinearReader::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(input, e))?
    {
        match record {
            Ok(mcap::records::Record::Metadata(m)) => w.write_metadata(&m).map_err(|e| mcap_err(output, e))?,
            Ok(_) => {}
            Err(_) => {
                complete = false;
                break;
            }
        }
    }
    let mut channels: HashMap<u16, u16> = HashMap::new();
    let mut schemas: HashMap<u16, u16> = HashMap::new();
    let mut messages = 0;
    for message in mcap::MessageStream::new_with_options(&bytes, mcap::read::Options::IgnoreEndMagic.into())
        .map_err(|e| mcap_err(input, e))?
    {
        let m = match message {
            Ok(m) => m,
            Err(_) => {
                complete = false;
                break;
            }
        };
        let channel_id = match channels.get(&m.channel.id) {
            Some(id) => *id,
            None => {
                let schema_id = match &m.channel.schema {
                    Some(s) => match schemas.get(&s.id) {
                        Some(id) => *id,
                        None => {
                            let id = w.add_schema(&s.name, &s.encoding, &s.data).map_err(|e| mcap_err(output, e))?;
                            schemas.insert(s.id, id);
                            id
                        }
                    },
                    None => 0,
                };
                let id = w
                    .add_channel(schema_id, &m.channel.topic, &m.channel.message_encoding, &m.channel.metadata)
                    .map_err(|e| mcap_err(output, e))?;
                channels.insert(m.channel.id, id);
                id
            }
        };
        w.write_to_known_channel(
            &mcap::records::MessageHeader {
                channel_id,
                sequence: m.sequence,
                log_time: m.log_time,
                publish_time: m.publish_time,
            },
            &m.data,
        )
        .map_err(|e| mcap_err(output, e))?;
        messages += 1;
    }
    w.finish().map_err(|e| mcap_err(output, e))?;
    Ok(Recovered { messages, complete })
}
