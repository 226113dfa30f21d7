//! DataStream's item types (`ViconCGStream/Enum.h`): the `u32` before every item's byte count, and the values
//! the `ObjectEnums`, `Contents` and `Filter` items list.

/// The tag that opens every packet.
pub const OBJECTS: u32 = 0x1A2B_0001;

// Control items (client and server).
pub const OBJECT_ENUMS: u32 = 100_001;
pub const REQUEST_FRAME: u32 = 100_002;
pub const KEEP_ALIVE: u32 = 100_003;
pub const CONTENTS: u32 = 100_004;
pub const START_MULTICAST_SENDER: u32 = 100_005;
pub const STOP_MULTICAST_SENDER: u32 = 100_006;
pub const FILTER: u32 = 100_007;
pub const REQUEST_NEXT_FRAME: u32 = 100_008;

// Static objects (resent when they change, else listed unchanged in `Contents`).
pub const STREAM_INFO: u32 = 1;
pub const SUBJECT_INFO: u32 = 2;
pub const DEVICE_INFO: u32 = 3;
pub const CHANNEL_INFO: u32 = 4;
pub const CAMERA_INFO: u32 = 14;
pub const SUBJECT_TOPOLOGY: u32 = 28;
pub const SUBJECT_HEALTH: u32 = 29;
pub const APPLICATION_INFO: u32 = 37;
pub const OBJECT_QUALITY: u32 = 40;

// Dynamic objects (one frame's).
pub const FRAME_INFO: u32 = 5;
pub const LABELED_RECONS: u32 = 6;
pub const UNLABELED_RECONS: u32 = 7;
pub const LOCAL_SEGMENTS: u32 = 8;
pub const GLOBAL_SEGMENTS: u32 = 9;
pub const LIGHTWEIGHT_SEGMENTS: u32 = 901;
pub const FORCE_FRAME: u32 = 10;
pub const VOLTAGE_FRAME: u32 = 13;
pub const CENTROIDS: u32 = 16;
pub const VIDEO_FRAME: u32 = 22;
pub const TIMECODE: u32 = 23;
pub const LATENCY_INFO: u32 = 26;
pub const HARDWARE_FRAME_INFO: u32 = 36;
pub const FRAME_RATE_INFO: u32 = 39;
pub const PING: u32 = 42;

/// The types impactd's client asks for: what a rigid subject and its labelled markers need.
pub const CLIENT_WANTS: [u32; 9] = [
    CONTENTS,
    STREAM_INFO,
    APPLICATION_INFO,
    SUBJECT_INFO,
    FRAME_INFO,
    TIMECODE,
    LATENCY_INFO,
    GLOBAL_SEGMENTS,
    LABELED_RECONS,
];

/// A type's name, for messages (the SDK's own names).
pub fn name(kind: u32) -> &'static str {
    match kind {
        OBJECT_ENUMS => "ObjectEnums",
        REQUEST_FRAME => "RequestFrame",
        KEEP_ALIVE => "KeepAlive",
        CONTENTS => "Contents",
        FILTER => "Filter",
        REQUEST_NEXT_FRAME => "RequestNextFrame",
        STREAM_INFO => "StreamInfo",
        SUBJECT_INFO => "SubjectInfo",
        APPLICATION_INFO => "ApplicationInfo",
        FRAME_INFO => "FrameInfo",
        LABELED_RECONS => "LabeledRecons",
        GLOBAL_SEGMENTS => "GlobalSegments",
        TIMECODE => "Timecode",
        LATENCY_INFO => "LatencyInfo",
        PING => "Ping",
        _ => "other",
    }
}
