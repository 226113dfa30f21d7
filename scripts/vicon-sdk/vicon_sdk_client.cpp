// The independent client of impactd's Vicon tests: Vicon's own DataStream SDK (C++, MIT, 1.11) reading a
// DataStream server, printing each frame it read as one JSON line on stdout.
//
//   vicon-sdk-client HOST:PORT push|pull FRAMES
//
// push: StreamMode::ServerPush (the server sends every frame); pull: StreamMode::ClientPull (one frame per
// GetFrame). It enables segment and marker data, skips the frames before the first one that names a subject
// (the server honours the object types asked for, which the SDK sends after its first read), then prints up to
// FRAMES frames: the SDK's frame number, rate, latency (total and each sample), timecode, the server's up axis,
// and per subject its root segment, each segment's parent, global translation (mm) and rotation matrix
// (row-major) with its occluded flag, and each marker's global translation and occluded flag; each frame
// number once (ClientPull can fetch a frame twice). Numbers are
// printed with 17 significant digits, so a double survives the trip exactly. Exit 0 once FRAMES frames were
// printed; 2 on bad arguments; 3 when it could not connect; 4 when the frames stopped coming (a 20 s guard).

#include "DataStreamClient.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>

using namespace ViconDataStreamSDK::CPP;

namespace
{
std::string Quote( const std::string & s )
{
  std::string out = "\"";
  for( char c : s )
  {
    switch( c )
    {
    case '"': out += "\\\""; break;
    case '\\': out += "\\\\"; break;
    case '\n': out += "\\n"; break;
    default:
      if( static_cast< unsigned char >( c ) < 0x20 )
      {
        char buf[ 8 ];
        std::snprintf( buf, sizeof buf, "\\u%04x", c );
        out += buf;
      }
      else
      {
        out += c;
      }
    }
  }
  return out + "\"";
}

std::string Num( double v )
{
  char buf[ 40 ];
  std::snprintf( buf, sizeof buf, "%.17g", v );
  return buf;
}

std::string Nums( const double * v, int n )
{
  std::string out = "[";
  for( int i = 0; i < n; ++i )
  {
    out += ( i ? "," : "" ) + Num( v[ i ] );
  }
  return out + "]";
}

std::string Bool( bool b )
{
  return b ? "true" : "false";
}

std::string FrameJson( Client & client, const std::string & mode )
{
  std::ostringstream o;
  o << "{\"mode\":" << Quote( mode );
  o << ",\"frame_number\":" << client.GetFrameNumber().FrameNumber;
  o << ",\"rate_hz\":" << Num( client.GetFrameRate().FrameRateHz );
  o << ",\"latency_total_s\":" << Num( client.GetLatencyTotal().Total );
  o << ",\"latency\":[";
  const unsigned int samples = client.GetLatencySampleCount().Count;
  for( unsigned int i = 0; i < samples; ++i )
  {
    const std::string name = client.GetLatencySampleName( i ).Name;
    o << ( i ? "," : "" ) << "{\"name\":" << Quote( name )
      << ",\"s\":" << Num( client.GetLatencySampleValue( name ).Value ) << "}";
  }
  o << "]";
  const Output_GetTimecode tc = client.GetTimecode();
  o << ",\"timecode\":{\"hours\":" << tc.Hours << ",\"minutes\":" << tc.Minutes << ",\"seconds\":" << tc.Seconds
    << ",\"frames\":" << tc.Frames << ",\"subframe\":" << tc.SubFrame << ",\"field\":" << Bool( tc.FieldFlag )
    << ",\"standard\":" << static_cast< int >( tc.Standard ) << ",\"subframes_per_frame\":" << tc.SubFramesPerFrame
    << ",\"user_bits\":" << tc.UserBits << "}";
  const Output_GetServerOrientation up = client.GetServerOrientation();
  o << ",\"up\":"
    << Quote( up.Result != Result::Success ? "unknown"
                                             : up.Orientation == ServerOrientation::YUp   ? "Y"
                                               : up.Orientation == ServerOrientation::ZUp ? "Z"
                                                                                          : "unknown" );
  o << ",\"subjects\":[";
  const unsigned int subjects = client.GetSubjectCount().SubjectCount;
  for( unsigned int s = 0; s < subjects; ++s )
  {
    const std::string subject = client.GetSubjectName( s ).SubjectName;
    o << ( s ? "," : "" ) << "{\"name\":" << Quote( subject );
    o << ",\"root\":" << Quote( client.GetSubjectRootSegmentName( subject ).SegmentName );
    o << ",\"segments\":[";
    const unsigned int segments = client.GetSegmentCount( subject ).SegmentCount;
    for( unsigned int g = 0; g < segments; ++g )
    {
      const std::string segment = client.GetSegmentName( subject, g ).SegmentName;
      const Output_GetSegmentGlobalTranslation t = client.GetSegmentGlobalTranslation( subject, segment );
      const Output_GetSegmentGlobalRotationMatrix r = client.GetSegmentGlobalRotationMatrix( subject, segment );
      o << ( g ? "," : "" ) << "{\"name\":" << Quote( segment )
        << ",\"parent\":" << Quote( client.GetSegmentParentName( subject, segment ).SegmentName )
        << ",\"translation_mm\":" << Nums( t.Translation, 3 ) << ",\"rotation\":" << Nums( r.Rotation, 9 )
        << ",\"occluded\":" << Bool( t.Occluded ) << ",\"rotation_occluded\":" << Bool( r.Occluded ) << "}";
    }
    o << "],\"markers\":[";
    const unsigned int markers = client.GetMarkerCount( subject ).MarkerCount;
    for( unsigned int m = 0; m < markers; ++m )
    {
      const std::string marker = client.GetMarkerName( subject, m ).MarkerName;
      const Output_GetMarkerGlobalTranslation t = client.GetMarkerGlobalTranslation( subject, marker );
      o << ( m ? "," : "" ) << "{\"name\":" << Quote( marker )
        << ",\"parent\":" << Quote( client.GetMarkerParentName( subject, marker ).SegmentName )
        << ",\"translation_mm\":" << Nums( t.Translation, 3 ) << ",\"occluded\":" << Bool( t.Occluded ) << "}";
    }
    o << "]}";
  }
  o << "]}";
  return o.str();
}
} // namespace

int main( int argc, char ** argv )
{
  if( argc != 4 )
  {
    std::fprintf( stderr, "usage: %s HOST:PORT push|pull FRAMES\n", argv[ 0 ] );
    return 2;
  }
  const std::string host = argv[ 1 ];
  const std::string mode = argv[ 2 ];
  const long frames = std::strtol( argv[ 3 ], nullptr, 10 );
  if( ( mode != "push" && mode != "pull" ) || frames <= 0 )
  {
    std::fprintf( stderr, "usage: %s HOST:PORT push|pull FRAMES\n", argv[ 0 ] );
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto guard = std::chrono::seconds( 20 );

  Client client;
  while( client.Connect( host ).Result != Result::Success )
  {
    if( std::chrono::steady_clock::now() - start > guard )
    {
      std::fprintf( stderr, "could not connect to %s\n", host.c_str() );
      return 3;
    }
    std::this_thread::sleep_for( std::chrono::milliseconds( 50 ) );
  }
  client.EnableSegmentData();
  client.EnableMarkerData();
  client.SetStreamMode( mode == "push" ? StreamMode::ServerPush : StreamMode::ClientPull );

  long printed = 0;
  unsigned int last = 0;
  while( printed < frames )
  {
    if( std::chrono::steady_clock::now() - start > guard )
    {
      std::fprintf( stderr, "only %ld of %ld frames came\n", printed, frames );
      return 4;
    }
    if( client.GetFrame().Result != Result::Success )
    {
      continue;
    }
    if( printed == 0 && client.GetSubjectCount().SubjectCount == 0 )
    {
      continue;
    }
    // ClientPull can fetch the same frame twice: each frame is printed once.
    const unsigned int number = client.GetFrameNumber().FrameNumber;
    if( printed > 0 && number == last )
    {
      continue;
    }
    last = number;
    std::printf( "%s\n", FrameJson( client, mode ).c_str() );
    std::fflush( stdout );
    ++printed;
  }
  client.Disconnect();
  return 0;
}
