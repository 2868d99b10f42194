// GDAL confined to local files of the documented formats (geometry/src/gdal_confinement.hpp).
// Every hostile input points at a listener on the loopback address that this test opens itself:
// each must be refused in one sentence and the listener must see no connection. The positive
// controls (a VRT over a DEM in its own folder reads the DEM's heights) keep the checks from
// refusing everything.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "swath/base/input_error.hpp"
#include "swath/geometry/field.hpp"
#include "swath/geometry/ground.hpp"

namespace swath::geometry {
namespace {

namespace fs = std::filesystem;

// A TCP listener on 127.0.0.1 at a port of the kernel's choice; connected() says whether anyone
// connected since it opened (the kernel completes the handshake into the backlog even though the
// test never accepts during the call).
class Listener {
 public:
  Listener() {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    EXPECT_EQ(::listen(fd_, 16), 0);
    socklen_t n = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &n);
    port_ = ntohs(a.sin_port);
    ::fcntl(fd_, F_SETFL, O_NONBLOCK);
  }
  ~Listener() { ::close(fd_); }
  Listener(const Listener&) = delete;
  Listener& operator=(const Listener&) = delete;
  std::string url(const std::string& file) const {
    return "http://127.0.0.1:" + std::to_string(port_) + "/" + file;
  }
  bool connected() const {
    const int c = ::accept(fd_, nullptr, nullptr);
    if (c < 0) return false;
    ::close(c);
    return true;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

fs::path confinement_scratch() {
  const fs::path dir =
      fs::temp_directory_path() / ("swath-gdal-confinement-" + std::to_string(::getpid()));
  static const bool made = [&] {
    fs::remove_all(dir);
    fs::create_directories(dir / "inner");
    return true;
  }();
  (void)made;
  return dir;
}

fs::path write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A 4 x 4 ESRI ASCII grid over the meadow (no CRS: longitude/latitude), height 400 + 10 column
// + row: plain text, so the test writes it without GDAL.
fs::path write_grid(const fs::path& path) {
  std::string t =
      "ncols 4\nnrows 4\nxllcorner 8.540\nyllcorner 47.396\ncellsize 0.001\nNODATA_value -9999\n";
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) t += std::to_string(400 + 10 * col + row) + " ";
    t += "\n";
  }
  return write(path, t);
}

std::string vrt_over(const std::string& source, bool relative) {
  return "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\">\n"
         "  <GeoTransform>8.540, 0.001, 0, 47.400, 0, -0.001</GeoTransform>\n"
         "  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n"
         "    <NoDataValue>-9999</NoDataValue>\n"
         "    <SimpleSource><SourceFilename relativeToVRT=\"" +
         std::string(relative ? "1" : "0") + "\">" + source +
         "</SourceFilename><SourceBand>1</SourceBand></SimpleSource>\n"
         "  </VRTRasterBand>\n</VRTDataset>\n";
}

const GeoPoint kInside{47.398, 8.5415, 0.0};

double height_m(const fs::path& dem) {
  return dem_ground(dem.string())->heights_m({kInside})[0];
}

// `f` throws base::InputError whose sentence holds `fragment`.
template <typename F>
void expect_refused(F f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected a refusal saying \"" << fragment << "\"";
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(GdalConfinement, AVrtDemInItsOwnFolderReadsTheDemsHeights) {
  const fs::path grid = write_grid(confinement_scratch() / "inner" / "dem.asc");
  const fs::path vrt =
      write(confinement_scratch() / "inner" / "dem.vrt", vrt_over("dem.asc", true));
  const double direct = height_m(grid);
  ASSERT_TRUE(std::isfinite(direct));
  EXPECT_NEAR(height_m(vrt), direct, 1e-6);
  // and by an absolute name inside the folder
  const fs::path vrt_abs =
      write(confinement_scratch() / "inner" / "dem-abs.vrt", vrt_over(grid.string(), false));
  EXPECT_NEAR(height_m(vrt_abs), direct, 1e-6);
}

TEST(GdalConfinement, AVrtDemReadsNothingOutsideItsFolder) {
  write_grid(confinement_scratch() / "outside.asc");
  const fs::path up =
      write(confinement_scratch() / "inner" / "up.vrt", vrt_over("../outside.asc", true));
  expect_refused([&] { height_m(up); }, "lies outside the VRT's folder");
  const fs::path passwd =
      write(confinement_scratch() / "inner" / "passwd.vrt", vrt_over("/etc/passwd", false));
  expect_refused([&] { height_m(passwd); }, "lies outside the VRT's folder");
  write(confinement_scratch() / "inner" / "secret.txt", "root:x:0:0:root:/root:/bin/bash\n");
  const fs::path raw = write(
      confinement_scratch() / "inner" / "raw.vrt",
      "<VRTDataset rasterXSize=\"8\" rasterYSize=\"4\"><VRTRasterBand dataType=\"Byte\" "
      "band=\"1\" subClass=\"VRTRawRasterBand\"><SourceFilename relativeToVRT=\"1\">secret.txt"
      "</SourceFilename><ImageOffset>0</ImageOffset><PixelOffset>1</PixelOffset><LineOffset>8"
      "</LineOffset></VRTRasterBand></VRTDataset>\n");
  expect_refused([&] { height_m(raw); }, "raw band");
}

// Heights no ground on Earth has are refused with their place, not flown: an SRTM void of
// -32768 in a grid without a NODATA value, a 1e30 fill. The same grid with its NODATA value
// declared reads (no height where the void is).
TEST(GdalConfinement, AGroundBeyondTheEarthsIsRefusedWithItsPlace) {
  for (const std::string fill : {"-32768", "1e30"}) {
    std::string t = "ncols 4\nnrows 4\nxllcorner 8.540\nyllcorner 47.396\ncellsize 0.001\n";
    for (int row = 0; row < 4; ++row) t += "400 410 " + fill + " 430\n";
    const fs::path void_grid = write(confinement_scratch() / ("void" + fill + ".asc"), t);
    expect_refused(
        [&] {
          dem_ground(void_grid.string())->heights_m({{47.398, 8.5425, 0}});
        },
        "beyond any on Earth");
    expect_refused(
        [&] {
          dem_ground(void_grid.string())->heights_m({{47.398, 8.5425, 0}});
        },
        "47.3980000, 8.5425000 (lat, lon)");
    const fs::path declared = write(confinement_scratch() / ("declared" + fill + ".asc"),
                                    t.insert(t.find("400"), "NODATA_value " + fill + "\n"));
    const auto h = dem_ground(declared.string())->heights_m({{47.398, 8.5405, 0}});
    EXPECT_NEAR(h[0], 400.0, 1e-6);
  }
}

TEST(GdalConfinement, NoDemOrAreaReachesTheNetwork) {
  const Listener listener;
  const fs::path remote_vrt = write(confinement_scratch() / "inner" / "remote.vrt",
                                    vrt_over("/vsicurl/" + listener.url("d.tif"), false));
  expect_refused([&] { height_m(remote_vrt); }, "is not a local file");
  expect_refused([&] { height_m("/vsicurl/" + listener.url("dem.tif")); }, "virtual path");
  const fs::path wms =
      write(confinement_scratch() / "wms.tif",
            "<GDAL_WMS><Service name=\"TMS\"><ServerUrl>" + listener.url("${z}/${x}/${y}.png") +
                "</ServerUrl></Service><DataWindow><UpperLeftX>-180</UpperLeftX>"
                "<UpperLeftY>90</UpperLeftY><LowerRightX>180</LowerRightX>"
                "<LowerRightY>-90</LowerRightY><TileLevel>1</TileLevel>"
                "</DataWindow></GDAL_WMS>\n");
  expect_refused([&] { height_m(wms); }, "not a raster GDAL reads");
  // An OGR VRT named like a GeoPackage, reading a URL and, second, a local GeoJSON: OGR's VRT
  // driver is not one swath reads, whatever the file is called.
  const fs::path ogr_vrt =
      write(confinement_scratch() / "area.gpkg",
            "<OGRVRTDataSource><OGRVRTLayer name=\"a\"><SrcDataSource>/vsicurl/" +
                listener.url("a.geojson") + "</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>\n");
  expect_refused([&] { read_field(ogr_vrt); }, "GDAL cannot open it");
  const fs::path local_json = write(
      confinement_scratch() / "square.geojson",
      R"({"type":"Polygon","coordinates":[[[8.54,47.39],[8.55,47.39],[8.55,47.40],[8.54,47.39]]]})");
  const fs::path ogr_vrt_local =
      write(confinement_scratch() / "local.gpkg",
            "<OGRVRTDataSource><OGRVRTLayer name=\"a\"><SrcDataSource>" + local_json.string() +
                "</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>\n");
  expect_refused([&] { read_field(ogr_vrt_local); }, "GDAL cannot open it");
  expect_refused([&] { read_field("/vsicurl/" + listener.url("a.gpkg")); }, "cannot open");
  expect_refused([&] { read_field("PG:dbname=swath host=127.0.0.1"); }, "cannot open");
  EXPECT_FALSE(listener.connected());
}

// A zip archive of one deflated member whose directory says it inflates to `inflated` bytes (the
// member itself is an empty deflate stream: nothing needs inflating to see the claim).
std::string zip_claiming(const std::string& member, std::uint32_t inflated) {
  auto le = [](std::string& out, std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
  };
  const std::string data("\x03\x00", 2);  // a final, empty fixed-Huffman block
  std::string z;
  le(z, 0x04034b50, 4);  // local file header
  for (const std::uint64_t v : {20u, 0u, 8u, 0u, 0u})
    le(z, v, 2);  // version, flags, deflate, time, date
  le(z, 0, 4);    // CRC-32 (not checked: nothing is inflated)
  le(z, data.size(), 4);
  le(z, inflated, 4);
  le(z, member.size(), 2);
  le(z, 0, 2);
  z += member + data;
  const std::size_t directory = z.size();
  le(z, 0x02014b50, 4);  // central directory header
  for (const std::uint64_t v : {20u, 20u, 0u, 8u, 0u, 0u}) le(z, v, 2);
  le(z, 0, 4);
  le(z, data.size(), 4);
  le(z, inflated, 4);
  le(z, member.size(), 2);
  for (int i = 0; i < 4; ++i) le(z, 0, 2);  // extra, comment, disk, internal attributes
  le(z, 0, 4);                              // external attributes
  le(z, 0, 4);                              // offset of the local header
  z += member;
  const std::size_t directory_size = z.size() - directory;
  le(z, 0x06054b50, 4);  // end of central directory
  for (const std::uint64_t v : {0u, 0u, 1u, 1u}) le(z, v, 2);
  le(z, directory_size, 4);
  le(z, directory, 4);
  le(z, 0, 2);
  return z;
}

TEST(GdalConfinement, AnArchiveThatInflatesBeyondTheLimitIsRefusedBeforeInflating) {
  const fs::path bomb =
      write(confinement_scratch() / "bomb.kmz", zip_claiming("doc.kml", 300u << 20));
  expect_refused([&] { read_field(bomb); }, "the archive inflates to 300 MiB");
  const fs::path zipped =
      write(confinement_scratch() / "bomb.zip", zip_claiming("a.geojson", 4000u << 20));
  expect_refused([&] { read_field(zipped); }, "the archive inflates to 4000 MiB");
  // Within the limit the claim passes the size check and the open says what GDAL found.
  const fs::path small =
      write(confinement_scratch() / "small.zip", zip_claiming("a.geojson", 1000));
  try {
    read_field(small);
  } catch (const base::InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("inflates"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace swath::geometry
